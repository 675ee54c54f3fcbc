// The sender's transmitter: one acoustic channel, so one frame on air at a time.
//
// Commands from any number of callers wait in one bounded queue (Stop goes to its front);
// a worker thread takes them one by one and sends each frame under a RetryController
// (seed Fig. 8): it plays the frame, waits for an answer of the frame's profile heard after
// the frame started (under the fast profile, an ACK must name the frame's sequence number),
// or for the ACK timeout, retransmits by itself, and then follows the command's policy (ask
// the caller, continue, or fail). A second thread listens to the microphone with every
// link's answer listener (ReplyListeners). Each command goes out under the profile its
// caller chose, or the transmitter's default. With a key, nothing goes on air without a MAC
// unless the operator allowed it (TransmitterOptions::allow_unauthenticated), and a Stop
// always goes authenticated: the robot refuses a frame without a MAC, and an untagged ACK
// is a fixed chord anyone within earshot can play (docs/security.md). Frames of a command
// go out in order with nothing between them but other frames of the same command and the
// joint renewals that fall due meanwhile; a cancelled command's queued frames never play, a
// chord already on air completes.
// It only emits progress events: the caller's stream reads them, and the observer it is
// given (store_recorder.h on a server) records them first.
// It drives one robot or several (RobotLinks: a name, a model, and links bound to the
// robot's address and key), all through its one loudspeaker: a command names its robot,
// and only that robot's answer confirms its frames (link/fast_link.h). A stop for every robot
// goes on links of its own, keyed with the room key (transmitter_room.cpp), and no robot
// answers it. Before each frame it listens before it talks (transmitter_air.cpp): the
// microphone's levels tell it whether another sender's frame or answer is on the air. While
// Teleop streams drive robots, it renews their velocity leases together, one frame for
// up to three robots, ahead of the queue (transmitter_renewal.cpp). The loudspeaker's
// thread is transmitter_loop.cpp, the microphone's transmitter_ears.cpp, a command's frames
// on air transmitter_send.cpp. What it puts on the air and hears there it publishes to its
// air's fan-out (air_fanout.h, transmitter_watch.cpp), for anyone to watch (WatchAir).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "air_fanout.h"
#include "command/robot_model.h"
#include "job.h"
#include "physical/audio_io.h"
#include "profile/link_profile.h"
#include "progress_observer.h"
#include "reliability/air_access.h"
#include "reliability/carrier_sense.h"
#include "renewal_schedule.h"
#include "reply_listeners.h"
#include "signal/spectrum_columns.h"
#include "transmitter_types.h"

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

  // Queues a command under sendable_profile(profile, command is a Stop). Throws QueueFull,
  // TransmitterUnavailable, UnauthenticatedRefused, command::ParameterError.
  std::shared_ptr<Job> submit(const command::Command& command, Policy policy,
                              std::chrono::milliseconds decision_timeout, bool to_front = false,
                              const LinkProfile* profile = nullptr, RobotIndex robot = 0);
  // Queues a stop for every robot in the room at the front, under `profile` (nullptr: the
  // first the room links have whose frames name robots), sent the profile's broadcast copies
  // and answered by none (link::TransmitFrame::broadcast). Throws RoomKeyMissing when a robot
  // has a key and the room links none; std::invalid_argument for a profile that names no
  // robot; and what submit() throws.
  std::shared_ptr<Job> submit_every_robot_stop(const LinkProfile* profile = nullptr);
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
  bool room_keyed() const { return room_links_.front()->keyed(); }
  // Answers the job awaiting a decision; false if no such job waits.
  bool decide(const std::string& command_id, reliability::Decision decision);
  // Commands submitted from now on belong to this test run (none: outside runs).
  void set_run(std::optional<std::string> run_id);
  // Finishes the chord on air, fails everything else as unavailable, stops the threads.
  void shutdown();

  const LinkProfile& profile() const { return profile_; }
  // The profile called `name` if this transmitter can send it; else std::invalid_argument.
  const LinkProfile& usable_profile(std::string_view name) const;
  // The link this transmitter sends `profile` to `robot` with.
  const link::Link& link_of(const LinkProfile& profile, RobotIndex robot = 0) const;
  // The robot called `name`; an empty name is the only robot. std::invalid_argument naming
  // the robots there are, for an unknown name or an empty one among several.
  RobotIndex robot_named(std::string_view name) const;
  const std::string& robot_name(RobotIndex robot) const { return robots_.at(robot).name; }
  const command::RobotModel& model_of(RobotIndex robot) const { return robots_.at(robot).model; }
  std::vector<RobotStatus> robots() const;
  AirShare air_share() const;
  // What it puts on the air and hears there, as it happens (air_event.h), for watchers.
  AirFanout& air_events() { return air_events_; }
  // The profile a command asking for `requested` (nullptr: the default) goes out under: that
  // one, unless this transmitter has a key and it carries no MAC. Then a Stop goes under the
  // first profile that does, and any other command is refused (UnauthenticatedRefused)
  // unless unauthenticated commands are allowed. std::invalid_argument for a profile this
  // transmitter cannot send.
  const LinkProfile& sendable_profile(const LinkProfile* requested, bool stop, RobotIndex robot = 0) const;

 private:
  struct HeardReply {
    HeardAnswer answer;
    double steady_ms;
  };

  std::shared_ptr<Job> enqueue(link::Link& link, const command::Command& command, Policy policy,
                               std::chrono::milliseconds decision_timeout, bool to_front);
  void run();
  void listen();
  void send(Job& job);
  // A frame no robot answers: played, and the command goes on.
  void send_unanswered(Job& job);
  // The renewals due now, played before the next frame of `job` (not its first).
  void renew_between_frames(const Job& job);
  // A joint renewal of `robots` (kept by keep_renewed), planned and played now.
  void send_renewal(const std::vector<RobotIndex>& robots);
  // Under mutex_: whether every robot a renewal renews is still kept (no stream of theirs ended).
  bool all_kept(const std::vector<Job::Renewed>& renewed) const;
  // Under mutex_: the robots whose renewal goes before the queue now (none while a Stop waits).
  std::vector<RobotIndex> renewals_due() const;
  // When the wait for the answer to `job`'s frame, which ended at `frame_end_ms`, ends: its
  // `deadline_ms`, or sooner, when a kept robot's renewal must go to be heard within its lease.
  double answer_wait_end_ms(const Job& job, double frame_end_ms, double deadline_ms) const;
  // One frame of `job` through the retry controller, `attempt` its state (seed Fig. 8).
  struct FrameAttempt;
  // Each false when the command ended there (cancelled, the loudspeaker failed, no decision).
  bool transmit(Job& job, FrameAttempt& attempt);
  void await_answer(Job& job, FrameAttempt& attempt);
  bool decide(Job& job, FrameAttempt& attempt);
  // To the observer, then to the job's caller, then to the air's watchers.
  void emit(Job& job, ProgressEvent event);
  // The air's events (transmitter_watch.cpp): what `event` of `job` shows of the air; an
  // answer the microphone read; a block's level (the air heard busy or quiet again) and its
  // spectrum, while someone watches it.
  void publish_air(const Job& job, const ProgressEvent& event);
  void publish_heard(const HeardAnswer& heard, double audio_ms, double level_dbfs);
  void publish_levels(std::span<const float> block, double end_audio_ms, bool busy, double level_dbfs,
                      double floor_dbfs);
  // The microphone's sample clock at `steady_ms` of the transmitter's steady clock.
  double audio_ms_of(double steady_ms) const;
  // Emits the command's last event and ends it.
  void end(Job& job, Outcome outcome, const std::string& detail);
  store::WallTime wall(double steady_ms) const;
  double now_ms() const;
  void play(const link::TransmitFrame& frame, double start_ms);
  // Waits until the loudspeaker is free and the air is ours (listen before talk), then marks
  // our exchange as begun; false if the job was cancelled or the transmitter stops meanwhile.
  // When the air holds the frame, it emits `waiting` (the attempt's event) as WaitingForAir,
  // with why; the job's air_wait() then holds how long it waited.
  bool wait_for_air(Job& job, ProgressEvent waiting);
  // Tells the operator (and the record) that `job`'s frame waits for the air: `wait` says why.
  void tell_waiting(Job& job, ProgressEvent waiting, const reliability::AirWait& wait, double now_ms);
  // Our frame ended: the microphone listens while we wait for its answer.
  void frame_ended();
  // Our exchange (a frame and its answer's wait) is over; `answer`: when our robot's answer
  // sounded (heard, or where its answers came lately), so that it is not taken for another's;
  // `unconfirmed`: no ACK came (a loss, perhaps a collision).
  void exchange_ended(std::optional<reliability::AirSpan> answer = std::nullopt, bool unconfirmed = false);
  // The longest silence between a frame's end and its answer that any profile this sender
  // knows allows (ack_timeout_ms − chord_ms): the quiet it waits for after another's sound.
  double answer_silence_ms() const;
  // Whether `answer`, read by `link`'s ear, came from a robot that is none of ours (only
  // formats whose answers name their robot can tell).
  bool another_robots(const link::Link& link, const link::Answer& answer) const;
  // The first answer to `frame` of `link` heard after `since_ms`, or nothing by `until_ms`.
  std::optional<HeardReply> wait_reply(const link::Link& link, const link::TransmitFrame& frame, double since_ms,
                                       double until_ms);
  link::Link& link_for(const LinkProfile& profile, RobotIndex robot = 0) const;
  // The robot's first link that authenticates its frames; std::invalid_argument if none does.
  const link::Link& authenticated_link(RobotIndex robot = 0) const;
  // The robot whose link `link` is.
  RobotIndex robot_of(const link::Link& link) const;
  // Under the lock: what a Stop for `link`'s robot (or every robot) ends (transmitter_stop.cpp).
  std::vector<std::shared_ptr<Job>> stop_overtakes(const link::Link& link, const command::Command& stop);
  void end_cancelled(Job& job);  // UNAVAILABLE while shutting down, else CANCELLED (a caller, a Stop)

  struct Robot {
    std::string name;
    command::RobotModel model;
    std::vector<std::unique_ptr<link::Link>> owned_links;
    std::vector<const link::Link*> links;      // what this transmitter can send it and hear from it
    std::optional<double> last_answered_ms;    // guarded by mutex_
    std::optional<double> answer_delay_ms;     // its last answer began this long after the frame ended (worker only)
    const link::Link* renewal_link = nullptr;  // kept renewed with it (keep_renewed); guarded by mutex_
    std::optional<double> renewed_ms;          // its last joint renewal's start; guarded by mutex_
    std::optional<double> frame_started_ms;    // its last frame's start, a renewal's too; guarded by mutex_
  };

  const LinkProfile& profile_;
  std::vector<Robot> robots_;
  std::vector<std::unique_ptr<link::Link>> room_links_;  // the stop for every robot
  std::unique_ptr<physical::AudioSink> speaker_;
  std::unique_ptr<physical::AudioSource> microphone_;
  ProgressObserver& observer_;
  TransmitterOptions options_;
  const std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::shared_ptr<Job> on_air_;
  std::deque<HeardReply> replies_;
  // The last answer from a robot none of ours read under our exchange, awaiting a second
  // (wait_reply): its address and when it was heard. Guarded by mutex_.
  std::optional<std::pair<unsigned, double>> masked_once_;
  std::optional<std::string> run_id_;
  std::string unavailable_;  // why the audio path failed, once it did
  bool stopping_ = false;
  // A Stop is queued behind a command on air, which it overtakes: waits for an answer end.
  bool stop_waiting_ = false;
  double channel_free_ms_ = 0;
  reliability::CarrierSense carrier_;  // fed by listen(), guarded by mutex_
  std::optional<reliability::AirAccess> air_;
  RenewalSchedule renewals_;  // guarded by mutex_

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
