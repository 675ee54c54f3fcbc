#include "renewal_schedule.h"

#include <algorithm>

namespace dtmf::server {

void RenewalSchedule::keep(Robot robot, double every_ms, double lease_ms, double now_ms) {
  const auto [it, added] = robots_.try_emplace(robot, Kept{every_ms, lease_ms, now_ms});
  it->second.every_ms = every_ms;
  it->second.lease_ms = lease_ms;
}

void RenewalSchedule::drop(Robot robot) { robots_.erase(robot); }

void RenewalSchedule::frame_started(Robot robot, double at_ms) {
  if (const auto it = robots_.find(robot); it != robots_.end())
    it->second.last_ms = std::max(it->second.last_ms, at_ms);
}

std::vector<RenewalSchedule::Robot> RenewalSchedule::due(double now_ms, std::size_t most) const {
  const auto next = next_due_ms();
  if (!next || *next > now_ms) return {};
  return oldest(most);
}

std::optional<double> RenewalSchedule::first_lease_end_ms() const {
  std::optional<double> first;
  for (const auto& [robot, k] : robots_)
    first = std::min(first.value_or(k.last_ms + k.lease_ms), k.last_ms + k.lease_ms);
  return first;
}

std::vector<RenewalSchedule::Robot> RenewalSchedule::oldest(std::size_t most) const {
  std::vector<std::pair<double, Robot>> by_age;
  for (const auto& [robot, k] : robots_) by_age.emplace_back(k.last_ms, robot);
  std::sort(by_age.begin(), by_age.end());
  std::vector<Robot> out;
  for (const auto& [last, robot] : by_age) {
    if (out.size() == most) break;
    out.push_back(robot);
  }
  return out;
}

std::optional<double> RenewalSchedule::next_due_ms() const {
  std::optional<double> next;
  for (const auto& [robot, k] : robots_) next = std::min(next.value_or(k.last_ms + k.every_ms), k.last_ms + k.every_ms);
  return next;
}

}  // namespace dtmf::server
