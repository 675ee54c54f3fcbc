#include "teleop_session.h"

#include <algorithm>
#include <chrono>

namespace dtmf::server {

TeleopSession::TeleopSession(command::RobotModel model, std::string driver)
    : model_(std::move(model)), driver_(std::move(driver)) {}

void TeleopSession::set_target(const command::Velocity& target, double now_s) {
  std::lock_guard lock(mutex_);
  target_ = target;
  heard_at_s_ = now_s;
}

void TeleopSession::end_stream() {
  std::lock_guard lock(mutex_);
  ended_ = true;
}

void TeleopSession::halt(const std::string& why) {
  std::function<void()> told;
  {
    std::lock_guard lock(mutex_);
    if (!halted_) halted_ = why;
    told = on_halt_;
  }
  if (told) told();
}

void TeleopSession::on_halt(std::function<void()> told) {
  std::lock_guard lock(mutex_);
  on_halt_ = std::move(told);
}

std::optional<command::Velocity> TeleopSession::frame_due(double now_s, bool renewed_jointly) {
  std::lock_guard lock(mutex_);
  if (in_flight_ || !target_ || ended_ || halted_ || now_s - heard_at_s_ > kClientSilence_s) return std::nullopt;
  const bool changed = !last_sent_ || *last_sent_ != *target_;
  const double renewed_s = std::max(sent_at_s_, renewed_at_s_.value_or(sent_at_s_));
  const bool renewal_due =
      last_sent_ && now_s - renewed_s >= last_sent_->lease_s * (renewed_jointly ? kJointRenewalLate : 0.5);
  const bool check_due = renewed_at_s_ && now_s - sent_at_s_ >= kCheckEvery_s;
  if (!changed && !renewal_due && !check_due && last_confirmed_) return std::nullopt;
  last_sent_ = target_;
  last_confirmed_ = false;
  in_flight_ = true;
  sent_at_s_ = now_s;
  renewed_at_s_.reset();
  return target_;
}

bool TeleopSession::renewable(double now_s) {
  std::lock_guard lock(mutex_);
  const bool live = target_ && !ended_ && !halted_ && now_s - heard_at_s_ <= kClientSilence_s;
  return live && last_sent_ && (last_sent_->linear_fraction != 0 || last_sent_->angular_fraction != 0);
}

void TeleopSession::renewed(double at_s) {
  std::lock_guard lock(mutex_);
  if (at_s > sent_at_s_) renewed_at_s_ = std::max(renewed_at_s_.value_or(at_s), at_s);
}

void TeleopSession::frame_ended(double now_s, bool answered, std::optional<command::Velocity> confirmed,
                                double response_time_ms) {
  std::lock_guard lock(mutex_);
  in_flight_ = false;
  window_.emplace_back(now_s, answered);
  forget_old(now_s);
  last_confirmed_ = confirmed.has_value();
  if (confirmed) {
    confirmed_ = confirmed;
    confirmed_at_s_ = now_s;
    response_time_ms_ = response_time_ms;
  }
}

void TeleopSession::forget_old(double now_s) {
  while (!window_.empty() && window_.front().first < now_s - kLinkWindow_s) window_.pop_front();
}

TeleopStatus TeleopSession::status(double now_s) {
  std::lock_guard lock(mutex_);
  forget_old(now_s);
  TeleopStatus s;
  if (target_) {
    s.target_linear_mps = command::linear_mps(model_, *target_);
    s.target_angular_radps = command::angular_radps(model_, *target_);
  }
  if (confirmed_) {
    s.confirmed =
        TeleopStatus::Confirmed{command::linear_mps(model_, *confirmed_), command::angular_radps(model_, *confirmed_)};
  }
  s.response_time_ms = response_time_ms_;
  s.frames_in_window = static_cast<int>(window_.size());
  const auto answered = std::count_if(window_.begin(), window_.end(), [](const auto& f) { return f.second; });
  s.link_quality = window_.empty() ? 0.0 : static_cast<double>(answered) / static_cast<double>(window_.size());
  // The robot heard the confirmed frame a little before its ACK came back: the lease left
  // is at most this.
  // A joint renewal since renews it (unconfirmed: renewals are not answered).
  const double held_from_s =
      renewed_at_s_ && last_confirmed_ ? std::max(confirmed_at_s_, *renewed_at_s_) : confirmed_at_s_;
  if (confirmed_) s.lease_left_s = std::max(0.0, confirmed_->lease_s - (now_s - held_from_s));
  return s;
}

bool TeleopSession::stream_ended() {
  std::lock_guard lock(mutex_);
  return ended_;
}

std::optional<std::string> TeleopSession::halted() {
  std::lock_guard lock(mutex_);
  return halted_;
}

double TeleopSession::silent_s(double now_s) {
  std::lock_guard lock(mutex_);
  return now_s - heard_at_s_;
}

std::optional<double> TeleopSession::next_change_s(double now_s, bool renewed_jointly) {
  std::lock_guard lock(mutex_);
  if (!target_ || ended_ || halted_) return std::nullopt;
  std::optional<double> first;
  const auto consider = [&](double at_s) {
    if (at_s > now_s && (!first || at_s < *first)) first = at_s;
  };
  // Silent for longer than kClientSilence_s (a strict test): just past it.
  constexpr double kJustPast_s = 0.001;
  consider(heard_at_s_ + kClientSilence_s + kJustPast_s);
  if (!in_flight_ && last_sent_) {
    const double renewed_s = std::max(sent_at_s_, renewed_at_s_.value_or(sent_at_s_));
    consider(renewed_s + last_sent_->lease_s * (renewed_jointly ? kJointRenewalLate : 0.5));
    if (renewed_at_s_) consider(sent_at_s_ + kCheckEvery_s);
  }
  return first;
}

}  // namespace dtmf::server
