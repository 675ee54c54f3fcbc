// SenderCore: the answers its ears heard. hear_answer() keeps each, with when it was heard;
// take_reply() takes from them the answer to the frame on air, and leaves the rest aside.
#include <spdlog/spdlog.h>

#include "link/answer_wait.h"
#include "sender_core.h"

namespace dtmf::server {

namespace {
// Another's robot is taken to answer under our exchanges once it has been read so twice within
// this: two senders in step read each other's robot's answers every exchange (about every
// 200 ms), while one answer of our own robots misread as naming another (the fleet teleop
// bench, three robots: once in 120 s) made the sender defer for 1.7 s and every lease lapse.
constexpr double kMaskedAgainMs = 5000;
// Answers kept for the frame on air: a few a frame at most (the ears hear each answer once);
// the oldest go first if nothing takes them.
constexpr std::size_t kKeptAnswers = 256;
}  // namespace

void SenderCore::hear_answer(const HeardAnswer& heard, double at_ms) {
  if (replies_.size() >= kKeptAnswers) replies_.pop_front();
  replies_.push_back({heard, at_ms});
  // Another's answer ends its exchange (reliability/air_access.h). Not a tag chord's
  // reading: the tag listener reads one out of noise or music up to every hop (talk-off,
  // benchmarks.md), where an ACK or a NACK is heard a hundred times an hour at most.
  if (!heard.answer.tag_reading) carrier_.answer_read(at_ms);
}

bool SenderCore::another_robots(const link::Link& link, const link::Answer& answer) const {
  // A tag chord names no robot, and the seed's answers name none either.
  if (answer.tag_reading || !link.addresses_robots()) return false;
  for (const Robot& r : robots_)
    for (const link::Link* l : r.links)
      if (l->addresses_robots() && l->options().address == answer.address) return false;
  return true;
}

std::optional<SenderCore::HeardReply> SenderCore::take_reply(const Sending& s) {
  const link::Link& link = s.job->link();
  const link::TransmitFrame& frame = *s.job->frames().at(static_cast<std::size_t>(s.index));
  const link::AnswerWait wait(link, frame);
  while (!replies_.empty()) {
    const HeardReply reply = replies_.front();
    replies_.pop_front();
    if (reply.at_ms < s.chord_start_ms || reply.answer.link != &link) continue;  // not an answer to this frame
    if (another_robots(link, reply.answer.answer)) {
      // Read under our exchange, where the microphone takes every sound for ours: another's
      // exchange went on under it unheard (reliability/carrier_sense.h, answer_masked).
      const unsigned address = reply.answer.answer.address;
      const bool again =
          masked_once_ && masked_once_->first == address && reply.at_ms - masked_once_->second <= kMaskedAgainMs;
      masked_once_ = std::pair{address, reply.at_ms};
      if (again) carrier_.answer_masked(reply.at_ms);
      spdlog::debug("an answer from robot {}, none of ours, while frame {} waits: {}", address,
                    frame.sequence.value_or(0),
                    again ? "another sender shares the air" : "once so far (a misread of ours?)");
      continue;
    }
    if (!wait.answered_by(reply.answer.answer)) {
      if (reply.answer.answer.tag_reading) continue;  // a tag chord spelling another tag
      spdlog::debug("an ACK naming frame {} while frame {} waits: late, ignored",
                    reply.answer.answer.sequence.value_or(0), frame.sequence.value_or(0));
      continue;
    }
    return reply;
  }
  return std::nullopt;
}

}  // namespace dtmf::server
