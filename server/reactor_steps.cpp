#include "reactor_steps.h"

#include <grpc/support/time.h>

#include <algorithm>
#include <cstdint>

namespace dtmf::server {

ReactorSteps::ReactorSteps(std::weak_ptr<void> owner, std::function<void()> step)
    : owner_(std::move(owner)), step_(std::move(step)) {}

void ReactorSteps::run() {
  {
    std::lock_guard lock(mutex_);
    if (running_) {
      again_ = true;
      return;
    }
    running_ = true;
  }
  while (true) {
    step_();
    std::lock_guard lock(mutex_);
    if (!again_) {
      running_ = false;
      return;
    }
    again_ = false;
  }
}

void ReactorSteps::run_at(std::chrono::steady_clock::time_point at) {
  // Alarms whose callbacks are done, destroyed after the lock is let go: destroying the last
  // gRPC object shuts gRPC down, which joins its executor threads, and one of them may be in
  // another alarm's callback, waiting for this lock (a test's hang, found 2026-12-07).
  std::list<Timer> done;
  std::lock_guard lock(mutex_);
  for (auto t = timers_.begin(); t != timers_.end();) {
    const auto next = std::next(t);
    if (t->fired) done.splice(done.end(), timers_, t);
    t = next;
  }
  if (std::any_of(timers_.begin(), timers_.end(), [at](const Timer& t) { return t.at <= at; })) return;
  Timer& timer = timers_.emplace_back();
  timer.at = at;
  // gRPC's alarms take its monotonic clock; the delay from now carries over.
  const auto delay_us = std::max<std::int64_t>(
      0, std::chrono::duration_cast<std::chrono::microseconds>(at - std::chrono::steady_clock::now()).count());
  const gpr_timespec due = gpr_time_add(gpr_now(GPR_CLOCK_MONOTONIC), gpr_time_from_micros(delay_us, GPR_TIMESPAN));
  timer.alarm.Set(due, [owner = owner_, this, &timer](bool ok) {
    const std::shared_ptr<void> alive = owner.lock();
    if (!ok || !alive) return;  // cancelled with its reactor
    fired(timer);
  });
}

void ReactorSteps::fired(Timer& timer) {
  {
    std::lock_guard lock(mutex_);
    timer.at = std::chrono::steady_clock::time_point::max();  // due no more: a new time is no longer covered by it
  }
  run();
  std::lock_guard lock(mutex_);
  timer.fired = true;  // its callback is done with it: run_at may destroy it now
}

}  // namespace dtmf::server
