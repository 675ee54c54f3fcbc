// Transmitter: listen before talk. The microphone's reader (listen()) feeds every block's
// level to the carrier sense; before each frame the loudspeaker's thread waits for the air
// (reliability/air_access.h), and marks its exchange so that its own sound is not taken
// for another's.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "transmitter.h"

namespace dtmf::server {

namespace {
// How often a frame waiting for the air looks whether its command was cancelled.
constexpr double kCancelCheckMs = 20;
}  // namespace

double Transmitter::answer_silence_ms() const {
  double longest = 0;
  const auto consider = [&longest](const link::Link& l) {
    longest = std::max(longest, l.profile().timing.ack_timeout_ms - l.profile().timing.chord_ms);
  };
  for (const Robot& r : robots_)
    for (const link::Link* l : r.links) consider(*l);
  for (const auto& l : room_links_) consider(*l);
  return longest;
}

bool Transmitter::wait_for_air(Job& job) {
  using reliability::AirUse;
  const AirUse use = std::holds_alternative<command::Stop>(job.command()) ? AirUse::Stop
                     : job.policy() == Policy::Live || job.renewal()      ? AirUse::Renewal
                                                                          : AirUse::Command;
  std::unique_lock lock(mutex_);
  while (true) {
    const double now = now_ms();
    double at = std::max(now, channel_free_ms_);
    if (air_) at = std::max(at, air_->start_at(carrier_, now, use));
    if (at <= now) {
      if (air_) {
        // Why it may start now: what tells a start into another's exchange from one it could not hear.
        const auto ago = [now](std::optional<double> t) { return t ? now - *t : -1.0; };
        spdlog::debug(
            "the air for command {}: starts at {:.0f} ms; another's sound {:.0f} ms ago, quiet for {:.0f} ms, "
            "another's answer read {:.0f} ms ago (-1: never, or not now)",
            job.id(), now, ago(carrier_.last_busy_ms()), ago(carrier_.quiet_since_ms()),
            ago(carrier_.answered_exchange_ms()));
        air_->started(carrier_, now);
      }
      carrier_.own_begin(now);
      return true;
    }
    if (stopping_ || job.cancelled()) return false;
    changed_.wait_for(lock, std::chrono::duration<double, std::milli>(std::min(at - now, kCancelCheckMs)));
  }
}

void Transmitter::frame_ended() {
  std::lock_guard lock(mutex_);
  carrier_.frame_ended(now_ms());
}

void Transmitter::exchange_ended(std::optional<reliability::AirSpan> answer, bool unconfirmed) {
  std::lock_guard lock(mutex_);
  const double now = now_ms();
  const std::size_t busy_before = carrier_.busy_blocks();
  carrier_.own_end(now, answer);
  if (carrier_.busy_blocks() > busy_before)
    spdlog::debug(
        "the air: {} blocks heard during our exchange, outside our answer ({:.0f}..{:.0f} ms, now {:.0f}), "
        "were another's",
        carrier_.busy_blocks() - busy_before, answer ? answer->from_ms : -1.0, answer ? answer->to_ms : -1.0, now);
  if (air_ && unconfirmed) air_->unanswered(carrier_, now);
}

AirShare Transmitter::air_share() const {
  std::lock_guard lock(mutex_);
  AirShare share;
  share.busy_blocks = carrier_.busy_blocks();
  share.others_answers = carrier_.others_answers();
  share.masked_answers = carrier_.masked_answers();
  if (air_) {
    share.deferred = air_->deferred();
    share.answered_waits = air_->answered_waits();
    share.yields = air_->yields();
    share.listens = air_->listens();
  }
  return share;
}

}  // namespace dtmf::server
