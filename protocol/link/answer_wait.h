// One transmission's wait for its answer: which answers heard answer the frame on air.
//
// A named ACK must name the frame and a tagged ACK spell its tag (Link::answers), in the
// frame's reply lane (link/reply_lane.h). A tagged ACK in that lane that does not spell the tag
// is a guess at the tag, whoever made it (an echo, the sender's own frames, a forger), and a
// transmission takes at most kTagGuessesPerAttempt of them: after that, no tagged ACK answers
// it, so a forger's chance per transmission stays bounded (docs/security.md). Pure logic: the
// caller starts a new wait for each transmission.
#pragma once

#include "link/link.h"
#include "reliability/reply_code.h"

namespace dtmf::link {

class AnswerWait {
 public:
  AnswerWait(const Link& link, const TransmitFrame& frame) : link_(link), frame_(frame) {}

  // Whether `answer` answers the frame (a NACK answers whatever frame is on air).
  bool answered_by(const Answer& answer) {
    // An ACK in another lane than the frame's cannot answer it, and is no guess at its tag:
    // the last answer's tail is read there.
    if (answer.ack && answer.lane != frame_.answer_lane) return false;
    const bool tagged = answer.tag_reading.has_value();
    if (tagged && guesses_ >= reliability::kTagGuessesPerAttempt) return false;  // the budget is spent
    if (link_.answers(answer, frame_)) return true;
    // A guess: a tagged reading that heard as many tones as a tag needs and spelt another
    // (read plainly: how it reads for this frame's tag decides only whether it answers).
    if (tagged && reliability::heard_tones(answer.tag_reading->plain) >= reliability::kTagTonesNeeded) ++guesses_;
    return false;
  }
  int guesses() const { return guesses_; }

 private:
  const Link& link_;
  const TransmitFrame& frame_;
  int guesses_ = 0;
};

}  // namespace dtmf::link
