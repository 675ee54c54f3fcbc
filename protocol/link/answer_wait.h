// One transmission's wait for its answer: which answers heard answer the frame on air.
//
// A named ACK must name the frame, in the frame's reply lane (link/reply_lane.h), and a tagged
// ACK spell its tag (Link::answers). A tagged reading that spells another tag is no more than a
// reading: the chance that a stranger's sound spells the one awaited is bounded per reading
// (reliability/tag_chord.h), so there is no budget of guesses, and the robot's true answer is
// heard whatever was played before it (docs/security.md). Pure logic: the caller starts a new
// wait for each transmission.
#pragma once

#include "link/link.h"

namespace dtmf::link {

class AnswerWait {
 public:
  AnswerWait(const Link& link, const TransmitFrame& frame) : link_(link), frame_(frame) {}

  // Whether `answer` answers the frame (a NACK answers whatever frame is on air).
  bool answered_by(const Answer& answer) const {
    // An untagged ACK in another lane than the frame's cannot answer it: the last answer's
    // tail is read there.
    if (answer.ack && !answer.tag_reading && answer.lane != frame_.answer_lane) return false;
    return link_.answers(answer, frame_);
  }

 private:
  const Link& link_;
  const TransmitFrame& frame_;
};

}  // namespace dtmf::link
