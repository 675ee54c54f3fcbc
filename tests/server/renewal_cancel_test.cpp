// A joint renewal that waits for the air when a stream ends (Transmitter::stop_renewing,
// docs/protocol.md §10): it never goes out for a robot whose stream ended. One did once, and
// stopped its robot 1327 ms after its client was killed (dtmf-bench-teleop, bound 1200 ms).
// On a free-field simulated air, an intruder's loudspeaker holds the air busy while the
// sender's renewal of its robots is due; a stream ends meanwhile. The waiting renewal is
// cancelled, and the next one renews only the robots whose streams go on. No agent is needed:
// nobody answers a renewal, and what goes on air is what the sender's observer sees start.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <numbers>
#include <optional>
#include <thread>

#include "fleet_system.h"
#include "transmitter.h"

using namespace dtmf;
using namespace std::chrono_literals;

namespace {

const LinkProfile& fast = profile_by_name("fast");
// Longer than a Teleop stream's 400 ms, so that both robots are kept before the first falls
// due: a renewal renews every robot kept, and two kept one after the other while the first was
// due already went out as two renewals under ctest's load.
constexpr double kRenewEveryMs = 2000;
constexpr double kLeaseMs = 2.5 * kRenewEveryMs;
constexpr auto kQuietFirst = 500ms;      // the carrier sense learns the room's floor
constexpr auto kWaitingFor = 200ms;      // how long the renewal has waited for the air when a stream ends
constexpr double kIntruderSoundS = 3.0;  // from before a renewal is due until after it; under kMaxDeferMs
constexpr double kIntruderHz = 1500;     // in the fast profile's band

// The renewals the sender queued (each waits for the air there) and the ones it started, with
// the robots each renews, and how each ended.
class Renewals : public server::ProgressObserver {
 public:
  struct Seen {
    std::string id;
    std::vector<std::string> robots;
  };
  void observe(const server::Job& job, const server::ProgressEvent& e) override {
    using Kind = server::ProgressEvent::Kind;
    if (!job.renewal()) return;
    Seen seen{job.id(), {}};
    for (const auto& r : job.renewed()) seen.robots.push_back(r.robot);
    std::sort(seen.robots.begin(), seen.robots.end());
    std::lock_guard lock(mutex_);
    if (e.kind == Kind::Queued) queued_.push_back(seen);
    if (e.kind == Kind::Transmitting) started_.push_back(seen);
    if (e.kind == Kind::Failed || e.kind == Kind::Sent) ended_.emplace_back(job.id(), e.outcome);
    changed_.notify_all();
  }
  // Waits up to `ms` for the first renewal queued; it, if any.
  std::optional<Seen> first_queued(std::chrono::milliseconds ms) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_for(lock, ms, [&] { return !queued_.empty(); })) return std::nullopt;
    return queued_.front();
  }
  // Waits up to `ms` for renewal `id` to end; how it ended.
  std::optional<server::Outcome> ended(const std::string& id, std::chrono::milliseconds ms) {
    std::unique_lock lock(mutex_);
    std::optional<server::Outcome> outcome;
    changed_.wait_for(lock, ms, [&] {
      for (const auto& [ended_id, o] : ended_)
        if (ended_id == id) outcome = o;
      return outcome.has_value();
    });
    return outcome;
  }
  // Waits up to `ms` for a renewal to start; the first that did.
  std::optional<Seen> first_started(std::chrono::milliseconds ms) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_for(lock, ms, [&] { return !started_.empty(); })) return std::nullopt;
    return started_.front();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Seen> queued_, started_;
  std::vector<std::pair<std::string, server::Outcome>> ended_;
};

std::vector<float> tone(double seconds) {
  std::vector<float> samples(static_cast<std::size_t>(seconds * fast.sample_rate_hz));
  for (std::size_t i = 0; i < samples.size(); ++i)
    samples[i] =
        0.3f *
        static_cast<float>(std::sin(2 * std::numbers::pi * kIntruderHz * static_cast<double>(i) / fast.sample_rate_hz));
  return samples;
}

server::RobotLinks robot(std::string name, std::uint8_t address) {
  server::RobotLinks r;
  r.name = std::move(name);
  link::LinkOptions o;
  o.address = address;
  r.links = link::make_links(o);
  return r;
}

struct WhatTheAirSaw {
  std::uint64_t busy_before_due = 0;             // blocks the sender heard busy before a renewal was due
  std::optional<Renewals::Seen> waiting;         // the renewal that waited for the air
  std::optional<server::Outcome> waiting_ended;  // how it ended
  std::optional<Renewals::Seen> first_played;    // the first renewal that went on air
  std::uint64_t deferred = 0;                    // frames that waited for the intruder's sound
};

// Sends `kept` robots (of alpha and beta) a velocity and keeps them renewed while the intruder
// holds the air; ends alpha's renewals while a renewal waits for the air, and keeps beta's (if
// kept) until the air has been free again.
WhatTheAirSaw end_alphas_stream_while_a_renewal_waits(std::size_t kept) {
  sim::ChannelConfig config;
  config.noise = sim::parse_noise("white", -70);
  sim::SimulatedAir air(fast.sample_rate_hz, config, 3);
  auto sender = air.add_station("sender", 0.0);
  auto intruder = air.add_station("intruder", 1.0);
  air.start();
  std::vector<server::RobotLinks> robots;
  robots.push_back(robot("alpha", 1));
  robots.push_back(robot("beta", 2));
  Renewals observer;
  server::TransmitterOptions options;
  options.backoff_seed = 3;
  server::Transmitter transmitter(std::move(robots), fast, std::move(sender.speaker), std::move(sender.microphone),
                                  observer, options);
  // As a server that starts: it hears the room's quiet before it sends. Its first sound
  // otherwise, the intruder's here, would become its noise floor (reliability/carrier_sense.h).
  std::this_thread::sleep_for(kQuietFirst);
  // A renewal renews the velocity its robot took last: one each, unanswered here.
  for (std::size_t r = 0; r < kept; ++r) {
    auto job =
        server::taken(transmitter.submit(command::Velocity{0.1, 0, 1.0}, server::Policy::Live, 1s, false, nullptr, r));
    while (!job->finished_and_drained()) job->next_event(100ms);
  }
  // The first is due kRenewEveryMs after alpha's velocity began: about 1.5 s from now.
  for (std::size_t r = 0; r < kept; ++r)
    EXPECT_TRUE(transmitter.keep_renewed(r, fast, kRenewEveryMs, kLeaseMs)) << "robot " << r;
  std::thread intruding([&] { intruder.speaker->write(tone(kIntruderSoundS)); });
  WhatTheAirSaw out;
  // The sender hears the air busy before a renewal is due.
  for (int k = 0; k < 100 && out.busy_before_due == 0; ++k) {
    std::this_thread::sleep_for(10ms);
    out.busy_before_due = transmitter.air_share().busy_blocks;
  }

  out.waiting = observer.first_queued(3s);
  std::this_thread::sleep_for(kWaitingFor);
  transmitter.stop_renewing(0);
  if (out.waiting) out.waiting_ended = observer.ended(out.waiting->id, 3s);
  out.first_played = observer.first_started(4s);
  if (kept > 1) transmitter.stop_renewing(1);
  out.deferred = transmitter.air_share().deferred;
  intruding.join();
  transmitter.shutdown();
  air.stop();
  return out;
}

}  // namespace

TEST(RenewalCancel, ARenewalWaitingForTheAirIsCancelledWhenItsOnlyStreamEnds) {
  const WhatTheAirSaw out = end_alphas_stream_while_a_renewal_waits(1);
  ASSERT_GT(out.busy_before_due, 0u) << "the sender never heard the intruder";
  ASSERT_TRUE(out.waiting) << "no renewal was due while the intruder held the air";
  ASSERT_TRUE(out.waiting_ended) << "the waiting renewal never ended";
  EXPECT_EQ(*out.waiting_ended, server::Outcome::Cancelled) << server::outcome_name(*out.waiting_ended);
  EXPECT_FALSE(out.first_played) << "a renewal went on air for a robot whose stream had ended";
  EXPECT_GE(out.deferred, 1u) << "the renewal never waited for the air";
}

TEST(RenewalCancel, TheRenewalAfterTheCancelledOneLeavesTheEndedStreamsRobotOut) {
  const WhatTheAirSaw out = end_alphas_stream_while_a_renewal_waits(2);
  ASSERT_GT(out.busy_before_due, 0u) << "the sender never heard the intruder";
  ASSERT_TRUE(out.waiting) << "no renewal was due while the intruder held the air";
  EXPECT_EQ(out.waiting->robots, (std::vector<std::string>{"alpha", "beta"}));
  ASSERT_TRUE(out.waiting_ended) << "the waiting renewal never ended";
  EXPECT_EQ(*out.waiting_ended, server::Outcome::Cancelled) << server::outcome_name(*out.waiting_ended);
  ASSERT_TRUE(out.first_played) << "beta's stream goes on, and no renewal went on air for it";
  EXPECT_EQ(out.first_played->robots, std::vector<std::string>{"beta"});
  // One deferral: the cancelled renewal's wait goes on for the next (AirAccess counts a frame's).
  EXPECT_GE(out.deferred, 1u) << "the renewals never waited for the air";
}
