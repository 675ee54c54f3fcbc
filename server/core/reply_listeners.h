// The sender's ears: every link's answer listener on the same microphone audio.
//
//   samples -> each link's AnswerListener (the seed's ACK / NACK chords, the fast profile's
//              ACK naming a sequence number, ...) -> one list of answers, each tagged with
//              the link that heard it
//
// The transmitter waits for an answer of the link of the frame on air, so each profile may
// send in its own way over one loudspeaker and one microphone. Times are milliseconds of
// audio since the first sample fed.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "link/link.h"

namespace dtmf::server {

struct HeardAnswer {
  const link::Link* link = nullptr;
  link::Answer answer;
};

class ReplyListeners {
 public:
  // All links must share one sample rate (they share one microphone).
  explicit ReplyListeners(std::span<const link::Link* const> links);
  std::vector<HeardAnswer> feed(std::span<const float> samples);
  // The block to read the microphone in: every listener's hop divides into it, so an answer
  // is heard as soon as its last window is in (the fast reply's hop is 4 ms).
  int block_samples() const { return block_samples_; }

 private:
  int block_samples_ = 0;
  std::vector<std::pair<const link::Link*, std::unique_ptr<link::AnswerListener>>> listeners_;
};

}  // namespace dtmf::server
