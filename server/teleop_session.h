// One live-driving stream (TeleopService::Teleop) as pure state: the newest target, when to
// send the next frame, what the robot confirmed, and the link's quality. No I/O and no
// clock: the caller passes the time (seconds on a steady scale), and it says when its rules
// next change (next_change_s), so that its stream looks again only then. Thread-safe: the
// stream's reads set targets while its step sends frames and reads the status, and another
// RPC may halt it.
//
// Sending rule: one frame at a time (nothing is due until the last has ended); a frame goes
// out when the target differs from the last one sent, when the last frame was not
// confirmed, or when half the lease has passed since the last was sent — so a lease
// survives a lost renewal, and a stale target is never sent again: only the newest is.
// Nothing is sent once the client has been silent for kClientSilence_s, has ended the
// stream, or a Stop overtook it; the lease then lapses on the robot.
// Joint renewals (fast links: Transmitter::keep_renewed) renew the lease between frames
// while the stream is renewable(); a renewal counts as a frame sent for the half-lease rule,
// so the stream's own frames then go out when the target changes, when the last was not
// confirmed, and every kCheckEvery_s: renewals are not answered, and only an answer shows
// that the robot still holds the velocity they renew (a restarted robot does not).
#pragma once

#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "command/command.h"
#include "command/robot_model.h"

namespace dtmf::server {

// A client that says nothing for this long has gone (a closed laptop, a lost network): its
// lease is no longer renewed. Clients repeat their target at least once a second.
inline constexpr double kClientSilence_s = 1.0;
// Link quality is counted over this much of the recent past.
inline constexpr double kLinkWindow_s = 3.0;
// While renewed jointly, a frame of the stream's own (answered) goes out at least this often.
inline constexpr double kCheckEvery_s = 5.0;
// A joint renewal is late when none began for this share of the lease: the stream renews the
// lease itself (a joint renewal starts at most 715 ms after the last: teleop_stream.cpp).
inline constexpr double kJointRenewalLate = 0.75;

// Velocities in the robot's units, the target's and the confirmed one's alike.
struct TeleopStatus {
  struct Confirmed {
    double linear_mps = 0;
    double angular_radps = 0;
  };
  double target_linear_mps = 0;
  double target_angular_radps = 0;
  std::optional<Confirmed> confirmed;  // as the robot executes it (the velocity its frame carried)
  double response_time_ms = 0;
  double link_quality = 0;  // answers heard per frame sent in the window
  int frames_in_window = 0;
  double lease_left_s = 0;
};

class TeleopSession {
 public:
  // `driver` names the client, for a refusal that tells another who drives the robot.
  explicit TeleopSession(command::RobotModel model, std::string driver = "");
  const std::string& driver() const { return driver_; }

  // The reader: a new target (a Velocity of the robot's model, already checked), heard at now_s.
  void set_target(const command::Velocity& target, double now_s);
  // The reader: the stream ended (the client half-closed, or it is gone).
  void end_stream();
  // Another RPC: a Stop overtook the stream. Calls on_halt's listener, outside the lock.
  void halt(const std::string& why);
  void on_halt(std::function<void()> told);

  // The next frame to send now, if one is due (and marks it sent). `renewed_jointly`: the
  // transmitter keeps the robot renewed (Transmitter::keep_renewed), so a lease is renewed by
  // a frame of the stream's own only when no renewal came for kJointRenewalLate of it.
  std::optional<command::Velocity> frame_due(double now_s, bool renewed_jointly = false);
  // Whether joint renewals should keep the robot's lease now: the stream is live and the
  // velocity last sent moves the robot (one at rest needs no lease).
  bool renewable(double now_s);
  // A joint renewal that renewed this robot began at `at_s`.
  void renewed(double at_s);
  // A frame sent ended: answered (ACK or NACK heard) or not; confirmed: the ACK, with the
  // velocity as the robot executes it, `response_time_ms` after its chord started.
  void frame_ended(double now_s, bool answered, std::optional<command::Velocity> confirmed, double response_time_ms);
  TeleopStatus status(double now_s);

  bool stream_ended();
  std::optional<std::string> halted();
  // Seconds since the client's last message.
  double silent_s(double now_s);
  // The first time after `now_s` at which frame_due() or renewable() may answer otherwise
  // with no new input (a renewal or a check due, the client turned silent); none while a
  // frame is in flight (its end is an input) or the stream is over.
  std::optional<double> next_change_s(double now_s, bool renewed_jointly);

 private:
  void forget_old(double now_s);

  const command::RobotModel model_;
  const std::string driver_;
  std::mutex mutex_;
  std::function<void()> on_halt_;
  std::optional<command::Velocity> target_;
  double heard_at_s_ = 0;
  std::optional<command::Velocity> last_sent_;
  double sent_at_s_ = 0;
  std::optional<double> renewed_at_s_;  // the last joint renewal's start, after sent_at_s_
  bool last_confirmed_ = false;
  bool in_flight_ = false;  // sent, and not yet ended
  std::optional<command::Velocity> confirmed_;
  double confirmed_at_s_ = 0;
  double response_time_ms_ = 0;
  std::deque<std::pair<double, bool>> window_;  // (frame ended at, answered)
  bool ended_ = false;
  std::optional<std::string> halted_;
};

}  // namespace dtmf::server
