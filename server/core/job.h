// One command in the sender: its frames, its policy, and the stream of progress events the
// caller reads. The sender's core (sender_core.h) plans it and decides its outcome, its driver
// (transmitter.h) hands its events over; the caller takes them (a pull tap, take_event(),
// told of each by on_event()), may cancel, and answers a pending decision. Thread-safe. A
// cancel or a decision wakes the driver (on_change), and an event its caller (on_event), so
// that each sees it at once: nobody polls a job.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "command/command.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/air_access.h"
#include "reliability/retry_controller.h"
#include "rows.h"

namespace dtmf::server {

// What to do with a frame the robot did not confirm after the profile's retransmissions.
// Live (teleop): send each frame once and go on; the next target, or the lease's renewal,
// is worth more than a stale one sent again.
// Unanswered: frames no robot answers (a stop for every robot): each played once, and done.
enum class Policy { Ask, Continue, Fail, Live, Unanswered };

// Sent: an unanswered command's frames all played.
enum class Outcome { Pending, Confirmed, Continued, Failed, Cancelled, Unavailable, Sent };
std::string outcome_name(Outcome outcome);

struct ProgressEvent {
  enum class Kind {
    Queued,
    Transmitting,
    Ack,
    Nack,
    NoAnswer,
    Retransmitting,
    AwaitingDecision,
    Confirmed,
    Continued,
    Failed,
    Sent,          // an unanswered command's frames all played
    WaitingForAir  // a frame's attempt began to wait for the air (listen before talk): why
  };
  explicit ProgressEvent(Kind k) : kind(k) {}
  Kind kind;
  int frame_index = 0;
  int attempt = 0;
  std::optional<double> response_time_ms;
  std::string detail;
  int queue_position = 0;
  store::WallTime time = store::WallClock::now();  // Transmitting, Retransmitting: when the chord started
  // The same three times on the sender core's clock (sender_core.h), from which its driver sets
  // the wall times above as it hands the event over.
  double at_ms = 0;
  std::optional<double> chord_ended_ms;
  std::optional<double> answered_ms;
  // For observers that keep a record (store_recorder.h):
  // The frame the event is about (none before the command's frames are planned, when it goes
  // on air), and how many frames the command has (its counter synchronisation included).
  std::shared_ptr<const link::TransmitFrame> frame;
  int frame_count = 0;
  Outcome outcome = Outcome::Pending;             // Confirmed, Continued, Failed: how the command ended
  std::optional<store::WallTime> chord_ended_at;  // Ack, Nack, NoAnswer: when this attempt's chord ended
  std::optional<store::WallTime> answered_at;     // Ack, Nack: when the answer was heard
  // Listen before talk (reliability/air_access.h). WaitingForAir: why ("sound 14 dB over the
  // room's floor"), and the longest it may still wait; Transmitting, Retransmitting: how long
  // this attempt waited (0: at once), and why if it did.
  std::string air_wait_reason;
  double air_wait_left_ms = 0;
  double air_wait_ms = 0;
  bool air_wait_bounded = false;  // ... and the command's bound, not a free air, ended it
};

class Job {
 public:
  // Throws command::ParameterError for a command the link cannot carry.
  Job(link::Link& link, command::Command command, Policy policy, std::chrono::milliseconds decision_timeout,
      std::optional<std::string> run_id);
  // A joint renewal (link::Link::plan_renewal), unanswered: its one frame, planned already, on
  // `link` (the first renewed robot's), for the robots named at their addresses. It carries no
  // command: each robot renews the velocity it took last (command() is a zero velocity).
  struct Renewed {
    std::size_t index = 0;  // its place among the sender's robots (RobotIndex)
    std::string robot;
    std::uint8_t address = 0;
  };
  Job(link::Link& link, link::TransmitFrame renewal, std::vector<Renewed> robots, std::optional<std::string> run_id);
  // The robots a joint renewal renews; empty for a command.
  const std::vector<Renewed>& renewed() const { return renewed_; }
  bool renewal() const { return !renewed_.empty(); }

  const std::string& id() const { return id_; }
  const command::Command& command() const { return command_; }
  link::Link& link() const { return link_; }
  const LinkProfile& profile() const { return link_.profile(); }
  // The frames, once planned (the transmitter's thread plans them as the command goes on air,
  // so that numbers and counters follow the order of the air, Stop's overtaking included).
  const std::vector<std::shared_ptr<const link::TransmitFrame>>& frames() const { return frames_; }
  void plan();
  // Frames planned, or before that the command's own (no synchronisation counted).
  int frame_count() const;
  Policy policy() const { return policy_; }
  const std::optional<std::string>& run_id() const { return run_id_; }
  // The robot it is for, by the name its sender gives it; empty for a stop for every robot.
  const std::string& robot() const { return robot_; }
  void set_robot(std::string name) { robot_ = std::move(name); }
  std::chrono::milliseconds decision_timeout() const { return decision_timeout_; }
  std::string description() const;

  // Caller side.
  std::optional<ProgressEvent> next_event(std::chrono::milliseconds timeout);
  // The next event if one is there; never waits.
  std::optional<ProgressEvent> take_event();
  // Called after each event and at the job's end, outside the job's lock, on the driver's
  // thread and under its locks: it must only note the news (a gRPC reactor runs its step on
  // gRPC's threads: reactor_steps.h), never call the transmitter.
  void on_event(std::function<void()> told);
  bool finished_and_drained();
  void cancel();
  bool decide(reliability::Decision decision);  // false unless a decision is awaited
  Outcome outcome();
  std::string outcome_detail();

  // Transmitter side.
  // Its waits for the air, all its frames' together (the transmitter's thread only).
  reliability::AirWait& air_wait() { return air_wait_; }
  void emit(ProgressEvent event);
  void finish(Outcome outcome, std::string detail = {});
  bool cancelled();
  // A Stop overtakes the command (SenderCore::submit): cancelled, and said so. It wakes no
  // one: the core that calls it is the one that reads it.
  void overtake();
  bool overtaken();
  // Opens the question before it is announced, so that a caller who answers the
  // AWAITING_DECISION event at once finds it open; take_decision() gives the answer once
  // decide() was called (nothing before: the core waits until its decision timeout).
  void open_decision();
  std::optional<reliability::Decision> take_decision();
  // Called (outside the job's lock) whenever cancel() or decide() changed it.
  void on_change(std::function<void()> wake);

 private:
  std::string id_ = store::new_id();
  link::Link& link_;
  command::Command command_;
  std::size_t command_frames_;
  std::vector<std::shared_ptr<const link::TransmitFrame>> frames_;
  Policy policy_;
  std::chrono::milliseconds decision_timeout_;
  std::optional<std::string> run_id_;
  std::string robot_;
  std::vector<Renewed> renewed_;
  reliability::AirWait air_wait_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ProgressEvent> events_;
  Outcome outcome_ = Outcome::Pending;
  std::string outcome_detail_;
  bool cancelled_ = false;
  bool overtaken_ = false;
  bool awaiting_decision_ = false;
  std::optional<reliability::Decision> decision_;
  std::function<void()> wake_;
  std::function<void()> told_;
  void woken();  // calls wake_, outside the lock
  void tell();   // calls told_, outside the lock
};

}  // namespace dtmf::server
