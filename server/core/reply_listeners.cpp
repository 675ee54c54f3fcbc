#include "reply_listeners.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::server {

ReplyListeners::ReplyListeners(std::span<const link::Link* const> links) {
  for (const link::Link* l : links) {
    if (l->profile().sample_rate_hz != links.front()->profile().sample_rate_hz) {
      throw std::invalid_argument("profiles " + links.front()->name() + " and " + l->name() +
                                  " use different sample rates and cannot share a microphone");
    }
    const int hop = l->answer_block_samples();
    block_samples_ = block_samples_ == 0 ? hop : std::min(block_samples_, hop);
    listeners_.emplace_back(l, l->answer_listener());
  }
}

std::vector<HeardAnswer> ReplyListeners::feed(std::span<const float> samples) {
  std::vector<HeardAnswer> answers;
  for (auto& [link, listener] : listeners_) {
    for (const link::Answer& answer : listener->feed(samples)) answers.push_back({link, answer});
  }
  return answers;
}

}  // namespace dtmf::server
