// The sender's transmitter: the driver of its core (core/sender_core.h) on one loudspeaker
// and one microphone. The core decides everything that goes on the air and when (the queue,
// a Stop's overtaking, listen before talk, retries, answers, renewals, the stop for every
// robot); this class gives it audio and time and does what it says:
//   - the loudspeaker's thread asks the core's next() and plays its frames; between them it
//     sleeps until the core's next time or until an input wakes it (no poll: an answer heard,
//     a command, a cancel, a decision; a block's level waits for the core's time);
//   - the microphone's thread reads blocks, runs the ears (ReplyListeners) outside the lock,
//     and hands the core each block's level and each answer heard;
//   - it hands the core's events, in order, to the observer (the record, store_recorder.h),
//     then to the job's caller, then to the air's watchers (air_fanout.h, transmitter_watch.cpp).
//     Publishing never waits for a watcher; the record's write() only queues.
// The core's clock is this class's steady clock in milliseconds; the microphone's blocks are
// mapped onto it as they are read. One lock guards the core; every call into it holds it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <thread>

#include "air_fanout.h"
#include "physical/audio_io.h"
#include "progress_observer.h"
#include "sender_core.h"
#include "signal/spectrum_columns.h"

namespace dtmf::server {

class Transmitter {
 public:
  // `links`: what it can send and hear (link::make_links, with the key if it has one);
  // `profile`: the default for commands that name none. Every link with the default's sample
  // rate can be chosen per command. With a key, a default without a MAC needs
  // `options.allow_unauthenticated` (else std::invalid_argument).
  Transmitter(std::vector<std::unique_ptr<link::Link>> links, const LinkProfile& profile,
              std::unique_ptr<physical::AudioSink> speaker, std::unique_ptr<physical::AudioSource> microphone,
              ProgressObserver& observer, TransmitterOptions options);
  // Several robots, each with its own links. Names and addresses must differ, and so must
  // keys (each key's counters are one sender's and one robot's); else std::invalid_argument.
  // `room_links`: what sends the stop for every robot (link::make_links with the room key,
  // program::room_link_options); none given: links without a key.
  Transmitter(std::vector<RobotLinks> robots, const LinkProfile& profile, std::unique_ptr<physical::AudioSink> speaker,
              std::unique_ptr<physical::AudioSource> microphone, ProgressObserver& observer, TransmitterOptions options,
              std::vector<std::unique_ptr<link::Link>> room_links = {});
  ~Transmitter();

  // Queues a command under sendable_profile(profile, command is a Stop), or refuses it
  // (SenderCore::submit; Unrecorded when its Queued cannot be recorded).
  Submitted submit(const command::Command& command, Policy policy, std::chrono::milliseconds decision_timeout,
                   bool to_front = false, const LinkProfile* profile = nullptr, RobotIndex robot = 0);
  // Queues a stop for every robot in the room at the front, under `profile` (nullptr: the
  // first the room links have whose frames name robots), sent the profile's broadcast copies
  // and answered by none (link::TransmitFrame::broadcast). Refused RoomKeyMissing when a robot
  // has a key and the room links none; NoProfile for a profile that names no robot; and as
  // submit() refuses.
  Submitted submit_every_robot_stop(const LinkProfile* profile = nullptr);
  // Teleop: keeps `robot`'s velocity lease (`lease_ms` from each frame's start) renewed every
  // `every_ms` by joint renewals under `profile` (link::Link::plan_renewal: one unanswered
  // frame for up to three robots), sent ahead of the queue (a Stop still goes first), until
  // stop_renewing(). False where that link cannot renew so (the seed's): the caller renews
  // with velocity frames of its own.
  bool keep_renewed(RobotIndex robot, const LinkProfile& profile, double every_ms, double lease_ms);
  void stop_renewing(RobotIndex robot);
  // When the last joint renewal that renewed `robot` began, if one did.
  std::optional<std::chrono::steady_clock::time_point> last_renewed(RobotIndex robot) const;
  // Whether the stop for every robot goes authenticated (the room links have a key).
  bool room_keyed() const { return core_.room_keyed(); }
  // Answers the job awaiting a decision; false if no such job waits.
  bool decide(const std::string& command_id, reliability::Decision decision);
  // Commands submitted from now on belong to this test run (none: outside runs).
  void set_run(std::optional<std::string> run_id);
  // Finishes the chord on air, fails everything else as unavailable, stops the threads.
  void shutdown();

  // What never changes after construction: read without the lock.
  const LinkProfile& profile() const { return core_.profile(); }
  // The profile called `name` if this transmitter can send it; else std::invalid_argument.
  const LinkProfile& usable_profile(std::string_view name) const { return core_.usable_profile(name); }
  // The link this transmitter sends `profile` to `robot` with.
  const link::Link& link_of(const LinkProfile& profile, RobotIndex robot = 0) const {
    return core_.link_of(profile, robot);
  }
  // The robot called `name`; an empty name is the only robot. std::invalid_argument naming
  // the robots there are, for an unknown name or an empty one among several.
  RobotIndex robot_named(std::string_view name) const { return core_.robot_named(name); }
  const std::string& robot_name(RobotIndex robot) const { return core_.robot_name(robot); }
  const command::RobotModel& model_of(RobotIndex robot) const { return core_.model_of(robot); }
  std::vector<RobotStatus> robots() const;
  AirShare air_share() const;
  // What it puts on the air and hears there, as it happens (air_event.h), for watchers.
  AirFanout& air_events() { return air_events_; }
  // The profile a command asking for `requested` (nullptr: the default) goes out under: that
  // one, unless this transmitter has a key and it carries no MAC. Then a Stop goes under the
  // first profile that does, and any other command is refused (UnauthenticatedRefused)
  // unless unauthenticated commands are allowed. std::invalid_argument for a profile this
  // transmitter cannot send.
  const LinkProfile& sendable_profile(const LinkProfile* requested, bool stop, RobotIndex robot = 0) const {
    return core_.sendable_profile(requested, stop, robot);
  }

 private:
  // Under `lock`: hands the core's events over, in order, outside the core's lock (the hand-over
  // lock keeps their order). A Queued the observer cannot record takes its job back: then why,
  // for a command's (a renewal's is only logged).
  std::optional<std::string> deliver(std::unique_lock<std::mutex>& lock);
  void deliver_one(SenderCore::Emitted& emitted);
  // A job the core took from a caller: it wakes the loudspeaker's thread when cancelled or
  // decided, and its Queued is handed over before the caller has it.
  Submitted accepted(std::unique_lock<std::mutex>& lock, Submitted submitted);
  // The loudspeaker's thread and the microphone's.
  void run();
  void listen();
  // Wakes the loudspeaker's thread: an input came. A job's cancel or decision calls it through
  // waker(), which does nothing once this transmitter is gone (a caller may keep its job).
  void wake();
  std::function<void()> waker();
  struct Waking {
    explicit Waking(Transmitter* t) : transmitter(t) {}
    std::mutex mutex;
    Transmitter* transmitter;
  };
  void play(const SenderCore::Play& play);
  // The air's events (transmitter_watch.cpp): what `event` of `job` shows of the air; an
  // answer the microphone read; a block's level (the air heard busy or quiet again) and its
  // spectrum, while someone watches it.
  void publish_air(const Job& job, const ProgressEvent& event);
  void publish_heard(const HeardAnswer& heard, double audio_ms, double level_dbfs);
  void publish_levels(std::span<const float> block, double end_audio_ms, bool busy, double level_dbfs,
                      double floor_dbfs);
  // The microphone's sample clock at `steady_ms` of the transmitter's steady clock.
  double audio_ms_of(double steady_ms) const;
  store::WallTime wall(double steady_ms) const;
  double now_ms() const;
  std::chrono::steady_clock::time_point steady(double steady_ms) const;

  std::unique_ptr<physical::AudioSink> speaker_;
  std::unique_ptr<physical::AudioSource> microphone_;
  ProgressObserver& observer_;
  bool realtime_audio_;
  const std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();

  mutable std::mutex mutex_;  // guards core_, inputs_, stopping_
  std::condition_variable woken_;
  SenderCore core_;
  std::uint64_t inputs_ = 0;  // counts what came in: the loudspeaker's thread sleeps until it moves
  bool stopping_ = false;
  std::mutex handing_;  // the core's events go out in order
  std::shared_ptr<Waking> waking_ = std::make_shared<Waking>(this);

  std::unique_ptr<ReplyListeners> ears_;  // every link's answer ear, fed by listen() alone
  AirFanout air_events_;
  // The steady clock less the microphone's sample clock, as of its last block (listen()).
  std::atomic<double> mic_offset_ms_{0};
  // The microphone reader's own: whether the air was last heard busy, and the spectrum's tap
  // (made while someone watches it) with the audio time it began at.
  bool air_busy_ = false;
  std::unique_ptr<signal::SpectrumColumns> columns_;
  double columns_start_ms_ = 0;
  std::thread worker_;
  std::thread listener_;
};

}  // namespace dtmf::server
