#include "link/fast_answer_listener.h"

#include "link/reply_lane.h"
#include "reliability/reply_code.h"

namespace dtmf::link {

namespace {

bool same(const Answer& a, const Answer& b) {
  return a.ack == b.ack && a.sequence == b.sequence && a.address == b.address && a.lane == b.lane;
}

}  // namespace

FastAnswerListener::FastAnswerListener(const LinkProfile& profile, bool keyed)
    : keyed_(keyed),
      needed_(profile.hops().reply_tones_needed),
      reply_ms_(1000.0 * profile.hops().reply_samples() / profile.sample_rate_hz),
      listener_(profile, profile.hops().reply_tones_needed) {
  if (keyed) tags_.emplace(profile);
}

std::span<const Answer> FastAnswerListener::feed(std::span<const float> samples) {
  answers_.clear();
  for (const signal::HeardReading& h : listener_.feed(samples)) {
    std::optional<Answer> now;
    auto named = reliability::read_reply(h.tones, needed_);
    // A named reply sounds only in its own lane: read in the other, it is its own edge
    // leaking two bins over, or its tail.
    if (named && h.lane != (named->ack ? answer_lane(named->sequence) : kNackLane)) named.reset();
    // Keyed, only NACKs are named: an ACK spells its tag (below).
    if (named && (!keyed_ || !named->ack))
      now = Answer{named->ack,   named->ack ? std::optional(named->sequence) : std::nullopt,
                   std::nullopt, h.heard_ms,
                   h.lane,       named->address};
    Previous& previous = previous_[static_cast<std::size_t>(h.lane)];
    if (now && previous.answer && h.window == previous.window + 1 && same(*previous.answer, *now)) pass(*now);
    previous = {now, h.window};
  }
  if (tags_) {
    for (const signal::HeardTagChord& t : tags_->feed(samples))
      answers_.push_back(Answer{true, std::nullopt, t.reading, t.heard_ms, 0});
  }
  return answers_;
}

void FastAnswerListener::pass(const Answer& a) {
  for (const Answer& before : recent_) {
    if (same(before, a) && a.heard_ms - before.heard_ms < reply_ms_) return;
  }
  recent_[next_++ % recent_.size()] = a;
  answers_.push_back(a);
}

}  // namespace dtmf::link
