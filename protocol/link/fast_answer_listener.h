// The fast profile's answer ear: readings of the reply bands (signal/hop_reply.h) and, keyed,
// of tag chords (signal/hop_tag_listener.h) -> answers.
//
// Named replies: ACK(sequence) or NACK, each only in its own lane (link/reply_lane.h), counted
// once two windows in a row read the same (a window straddling a chord's start reads a tone
// or two wrong). Keyed, NACKs so, and every reading of a tag chord that heard as many bands as a
// tag needs as a tagged ACK, which the sender checks against the tag it waits for (one window
// may be the only one a notch leaves clear; Link::answers). The same named answer again within
// a reply's length is that reply, passed once.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "link/link.h"
#include "signal/hop_reply.h"
#include "signal/hop_tag_listener.h"

namespace dtmf::link {

class FastAnswerListener final : public AnswerListener {
 public:
  FastAnswerListener(const LinkProfile& profile, bool keyed);
  std::span<const Answer> feed(std::span<const float> samples) override;

 private:
  void pass(const Answer& a);

  bool keyed_;
  int needed_;
  double reply_ms_;
  signal::HopReplyListener listener_;
  std::optional<signal::HopTagListener> tags_;  // keyed senders only
  struct Previous {
    std::optional<Answer> answer;
    long long window = -10;
  };
  std::array<Previous, HopPlan::kReplyLanes> previous_{};  // the last reading of each lane
  std::array<Answer, 4> recent_{};
  std::size_t next_ = 0;
  std::vector<Answer> answers_;
};

}  // namespace dtmf::link
