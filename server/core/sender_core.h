// The sender's core: every decision of what goes on the air and when, as pure state. No I/O,
// no thread, no clock: time comes in with every call (`now_ms`, one monotonic millisecond
// scale the driver chooses: the live transmitter's steady clock, with the microphone's blocks
// mapped onto it; a benchmark's sample count). Like the robot's receive path it is clocked by
// its audio: the microphone's blocks come in as hear_level() and hear_answer(), and between
// them the driver asks next() what the loudspeaker does now.
//
//   submit(command) ─┐                      ┌─> Play{frame}        the driver plays it, asks again
//   hear_level()   ──┼──> SenderCore::next ─┼─> WaitUntil{t}       ... at t, or at the next input
//   hear_answer()  ──┘                      └─> Idle               ... at the next input
//   take_events() -> (job, ProgressEvent) in order: for the record, the caller, the watchers
//
// It holds what the transmitter's threads did before: one bounded queue (a Stop at its
// front, overtaking what it stops), carrier sense and air access (listen before talk), each
// frame's retry controller (seed Fig. 8), the match of answers to the frame on air, joint
// renewals of leases (between a command's frames too), the stop for every robot, and the
// caller's decision when retransmissions are used up. A job's cancel or decision is read at
// the next call (Job::on_change wakes the driver). Not thread-safe: its driver holds one lock
// around every call (transmitter.h); benchmarks and tests call it from one thread.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "job.h"
#include "refusal.h"
#include "reliability/air_access.h"
#include "reliability/carrier_sense.h"
#include "renewal_schedule.h"
#include "reply_listeners.h"
#include "transmitter_types.h"

namespace dtmf::server {

// A command the sender took (its job), or why it refused it.
using Submitted = std::variant<std::shared_ptr<Job>, Refusal>;
// The job, for a caller sure it was taken (tests, benchmarks); std::logic_error with the
// refusal's why otherwise.
inline std::shared_ptr<Job> taken(Submitted submitted) {
  if (auto* refusal = std::get_if<Refusal>(&submitted)) throw std::logic_error("refused: " + refusal->why);
  return std::get<std::shared_ptr<Job>>(std::move(submitted));
}

class SenderCore {
 public:
  // Put `frame` of `job` on the air now (`start_ms`); its end is the core's to know.
  struct Play {
    std::shared_ptr<Job> job;
    std::shared_ptr<const link::TransmitFrame> frame;
    double start_ms = 0;
  };
  // Nothing to do until `at_ms`, unless an input comes first.
  struct WaitUntil {
    double at_ms = 0;
  };
  // Nothing to do until an input comes.
  struct Idle {};
  using Step = std::variant<Play, WaitUntil, Idle>;
  struct Emitted {
    std::shared_ptr<Job> job;
    ProgressEvent event;
  };
  struct RobotHeard {
    RobotIndex robot = 0;
    std::optional<double> last_answered_ms;
  };

  // As Transmitter's constructors (transmitter.h) say, and with the same refusals.
  SenderCore(std::vector<RobotLinks> robots, const LinkProfile& profile, TransmitterOptions options,
             std::vector<std::unique_ptr<link::Link>> room_links);

  // Inputs.
  // Queues a command (a Stop at the front, overtaking what it stops); its Queued event is the
  // next taken. Or refuses it: QueueFull, Unavailable, Unauthenticated, Unsendable, NoProfile.
  Submitted submit(const command::Command& command, Policy policy, std::chrono::milliseconds decision_timeout,
                   bool to_front, const LinkProfile* profile, RobotIndex robot, double now_ms);
  // The stop for every robot, on the room links (transmitter.h); refused RoomKeyMissing too.
  Submitted submit_every_robot_stop(const LinkProfile* profile, double now_ms);
  // Takes back a job whose Queued event could not be recorded: it never goes on the air. Only
  // before it played (its driver calls it as it hands the Queued event over).
  void withdraw(const Job& job, double now_ms);
  bool keep_renewed(RobotIndex robot, const LinkProfile& profile, double every_ms, double lease_ms, double now_ms);
  void stop_renewing(RobotIndex robot);
  void set_run(std::optional<std::string> run_id) { run_id_ = std::move(run_id); }
  // A microphone block of `level_dbfs` ended at `at_ms`.
  void hear_level(double level_dbfs, double at_ms);
  // An answer its ears (ReplyListeners) read, heard at `at_ms`.
  void hear_answer(const HeardAnswer& heard, double at_ms);
  // The loudspeaker or the microphone failed: the frame on air ends, and so does every command.
  void audio_failed(std::string why, double now_ms);
  // From now on nothing new goes on the air; next() ends what waits as unavailable.
  void shutdown();

  // The loudspeaker's next step at `now_ms`.
  Step next(double now_ms);
  // The events made since the last call, in order.
  std::vector<Emitted> take_events() { return std::exchange(events_, {}); }
  // After shutdown(): nothing is on the air or waits any more.
  bool finished() const { return stopping_ && !sending_ && queue_.empty(); }

  // What it knows.
  const LinkProfile& profile() const { return profile_; }
  const LinkProfile& usable_profile(std::string_view name) const;
  const link::Link& link_of(const LinkProfile& profile, RobotIndex robot = 0) const { return link_for(profile, robot); }
  const LinkProfile& sendable_profile(const LinkProfile* requested, bool stop, RobotIndex robot = 0) const;
  RobotIndex robot_named(std::string_view name) const;
  std::size_t robot_count() const { return robots_.size(); }
  const std::string& robot_name(RobotIndex robot) const { return robots_.at(robot).name; }
  const command::RobotModel& model_of(RobotIndex robot) const { return robots_.at(robot).model; }
  const link::LinkOptions& robot_options(RobotIndex robot) const { return robots_.at(robot).links.front()->options(); }
  std::optional<double> last_answered_ms(RobotIndex robot) const { return robots_.at(robot).last_answered_ms; }
  std::optional<double> last_renewed_ms(RobotIndex robot) const { return robots_.at(robot).renewed_ms; }
  bool room_keyed() const { return room_links_.front()->keyed(); }
  // Every link whose answers its ears listen for, robots' and room's.
  std::vector<const link::Link*> every_link() const;
  std::shared_ptr<Job> on_air() const { return sending_ ? sending_->job : nullptr; }
  const std::string& unavailable() const { return unavailable_; }
  AirShare air_share() const;
  // Whether the air is heard busy with another's sound now, and the room's floor.
  bool busy_now() const { return carrier_.busy_now(); }
  double floor_dbfs() const { return carrier_.floor_dbfs(); }

 private:
  struct Robot {
    std::string name;
    command::RobotModel model;
    std::vector<std::unique_ptr<link::Link>> owned_links;
    std::vector<const link::Link*> links;      // what it can send the robot and hear from it
    std::optional<double> last_answered_ms;    // its last answer heard
    std::optional<double> answer_delay_ms;     // its last answer began this long after the frame ended
    const link::Link* renewal_link = nullptr;  // kept renewed with it (keep_renewed)
    std::optional<double> renewed_ms;          // its last joint renewal's start
    std::optional<double> frame_started_ms;    // its last frame's start, a renewal's too
  };
  // The job on air, one frame's attempt at a time.
  struct Sending {
    enum class Phase { NextFrame, Air, Playing, Answer, Decision };
    explicit Sending(std::shared_ptr<Job> sent) : job(std::move(sent)) {}
    std::shared_ptr<Job> job;
    Phase phase = Phase::NextFrame;
    int index = -1;  // the frame
    std::optional<reliability::RetryController> retry;
    bool continued = false;
    double chord_start_ms = 0;
    double chord_end_ms = 0;
    double answer_until_ms = 0;
    std::optional<double> decision_until_ms;  // a question asked: when its time runs out
    // The renewals due went before this attempt: it goes next, whatever falls due meanwhile.
    bool renewed_before = false;
    // A renewal of a robot whose stream ended meanwhile (stop_renewing): it does not play.
    bool dropped = false;
    // Whether it ends before its next frame: cancelled, dropped, or the sender stops.
    bool ending(bool stopping) const { return stopping || dropped || job->cancelled(); }
  };
  struct HeardReply {
    HeardAnswer answer;
    double at_ms;
  };
  // What a phase of next() says: a step to give the driver, or nothing (go on deciding).
  using MaybeStep = std::optional<Step>;

  void add_robot(RobotLinks given);
  void check_default_profile(RobotIndex robot) const;
  Submitted enqueue(link::Link& link, const command::Command& command, Policy policy,
                    std::chrono::milliseconds decision_timeout, bool to_front, double now_ms);
  std::vector<std::shared_ptr<Job>> stop_overtakes(const link::Link& link, const command::Command& stop);
  void emit(const std::shared_ptr<Job>& job, ProgressEvent event, double at_ms);
  ProgressEvent attempt_event(const Sending& s, ProgressEvent::Kind kind) const;
  // Emits the command's last event and ends it; the job on air is done.
  void end(Sending& s, Outcome outcome, const std::string& detail, double now_ms);
  void end_cancelled(Sending& s, double now_ms);
  // Ends every queued command so, before it went on the air.
  void end_queued(Outcome outcome, const std::string& detail, double now_ms);
  // The next job on the air: a renewal due, or the queue's front. False when there is none.
  bool take_next(double now_ms);
  Step idle_step() const;
  // The phases of the job on air (sender_core_frames.cpp), and the one `s` is in.
  MaybeStep phase_step(Sending& s, double now_ms);
  MaybeStep next_frame(Sending& s, double now_ms);
  MaybeStep await_air(Sending& s, double now_ms);
  MaybeStep play(Sending& s, double now_ms);
  MaybeStep playing(Sending& s, double now_ms);
  MaybeStep await_answer(Sending& s, double now_ms);
  MaybeStep await_decision(Sending& s, double now_ms);
  void answered(Sending& s, const std::optional<HeardReply>& reply, double now_ms);
  // Listen before talk (sender_core_air.cpp).
  reliability::AirUse air_use(const Job& job) const;
  void tell_waiting(Sending& s, const reliability::AirWait& wait, double now_ms);
  void exchange_ended(double now_ms, std::optional<reliability::AirSpan> answer = std::nullopt,
                      bool unconfirmed = false);
  double answer_silence_ms() const;
  // Answers (sender_core_ears.cpp): the first heard that answers `s`'s frame, if any yet.
  std::optional<HeardReply> take_reply(const Sending& s);
  bool another_robots(const link::Link& link, const link::Answer& answer) const;
  // Renewals (sender_core_renewal.cpp).
  std::vector<RobotIndex> renewals_due(double now_ms) const;
  bool all_kept(const std::vector<Job::Renewed>& renewed) const;
  // Starts a joint renewal of `robots` as the job on air (the command on air, if any, waits
  // behind it); false if none could be planned.
  bool start_renewal(const std::vector<RobotIndex>& robots, double now_ms);
  double answer_wait_end_ms(const Job& job, double frame_end_ms, double deadline_ms) const;
  void frame_started(const Job& job, double at_ms);

  link::Link& link_for(const LinkProfile& profile, RobotIndex robot = 0) const;
  const link::Link& authenticated_link(RobotIndex robot = 0) const;
  RobotIndex robot_of(const link::Link& link) const;

  const LinkProfile& profile_;
  TransmitterOptions options_;
  std::vector<Robot> robots_;
  std::vector<std::unique_ptr<link::Link>> room_links_;  // the stop for every robot

  std::deque<std::shared_ptr<Job>> queue_;
  std::optional<Sending> sending_;  // the job on air
  std::optional<Sending> between_;  // the command a renewal goes between the frames of
  std::deque<HeardReply> replies_;
  // The last answer from a robot none of ours read under our exchange, awaiting a second
  // (take_reply): its address and when it was heard.
  std::optional<std::pair<unsigned, double>> masked_once_;
  std::optional<std::string> run_id_;
  std::string unavailable_;  // why the audio path failed, once it did
  bool stopping_ = false;
  // A Stop is queued behind a command on air, which it overtakes: ends its answer's wait.
  bool stop_waiting_ = false;
  double channel_free_ms_ = 0;
  reliability::CarrierSense carrier_;
  std::optional<reliability::AirAccess> air_;
  RenewalSchedule renewals_;
  std::vector<Emitted> events_;
};

}  // namespace dtmf::server
