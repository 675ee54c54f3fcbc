#include "reply_listeners.h"

#include <algorithm>
#include <stdexcept>

namespace dtmf::server {

ReplyListeners::ReplyListeners(std::span<const LinkProfile* const> profiles) {
  for (const LinkProfile* p : profiles) {
    if (p->sample_rate_hz != profiles.front()->sample_rate_hz) {
      throw std::invalid_argument("profiles " + profiles.front()->name + " and " + p->name +
                                  " use different sample rates and cannot share a microphone");
    }
    const int hop = p->frame_format == FrameFormat::Command48 ? p->bins.reply_hop_samples : p->hop_samples();
    block_samples_ = block_samples_ == 0 ? hop : std::min(block_samples_, hop);
    if (p->frame_format == FrameFormat::Command48) named_listeners_.emplace_back(p, std::make_unique<signal::BinReplyListener>(*p));
    else chord_listeners_.push_back(std::make_unique<ChordEar>(*p));
  }
}

std::vector<HeardAnswer> ReplyListeners::feed(std::span<const float> samples) {
  std::vector<HeardAnswer> answers;
  for (auto& ear : chord_listeners_) {
    for (const signal::Heard& heard : ear->listener.feed(samples)) {
      answers.push_back({ear->profile, static_cast<signal::Reply>(heard.symbol) == signal::Reply::Ack, std::nullopt, heard.heard_ms});
    }
  }
  for (auto& [profile, listener] : named_listeners_) {
    for (const signal::HeardReply& heard : listener->feed(samples)) {
      HeardAnswer answer{profile, heard.reply.ack, std::nullopt, heard.heard_ms};
      if (heard.reply.ack) answer.sequence = heard.reply.sequence;
      answers.push_back(answer);
    }
  }
  return answers;
}

}  // namespace dtmf::server
