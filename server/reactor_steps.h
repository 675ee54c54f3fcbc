// Runs a gRPC reactor's step whenever an input comes, one step at a time, with no thread and
// no poll of its own (a stream as a small reactor, as in gRPC's route_guide callback server):
//   - run(): now, on this thread: a gRPC reaction's (OnReadDone, OnWriteDone, OnCancel), which
//     holds none of the sender's locks;
//   - run_soon(): from a thread that may hold the transmitter's locks (a job's event is handed
//     over under them, and a step calls the transmitter): on gRPC's callback threads, through a
//     grpc::Alarm due now;
//   - run_at(t): at t, the same way: the time a reactor's rules name (a lease's renewal due, a
//     client gone silent), so that nothing looks at the clock in between.
// An input that comes during a step makes one more step after it, so that none is lost and
// steps never overlap. The reactor owns this and is itself owned by a shared pointer: an alarm
// that fires after the reactor is gone finds it expired and does nothing.
#pragma once

#include <grpcpp/alarm.h>

#include <chrono>
#include <functional>
#include <list>
#include <memory>
#include <mutex>

namespace dtmf::server {

class ReactorSteps {
 public:
  // `owner` keeps this alive while an alarm's step runs; `step` is its reactor's.
  ReactorSteps(std::weak_ptr<void> owner, std::function<void()> step);
  ReactorSteps(const ReactorSteps&) = delete;
  ReactorSteps& operator=(const ReactorSteps&) = delete;

  void run();
  void run_soon() { run_at(std::chrono::steady_clock::now()); }
  // A step at `at`, unless one is due by then already.
  void run_at(std::chrono::steady_clock::time_point at);

 private:
  struct Timer {
    grpc::Alarm alarm;
    std::chrono::steady_clock::time_point at;
    bool fired = false;
  };
  void fired(Timer& timer);

  std::weak_ptr<void> owner_;
  std::function<void()> step_;
  std::mutex mutex_;
  bool running_ = false;
  bool again_ = false;
  // Pending alarms, and those whose callbacks are done (`fired`), which the next run_at()
  // destroys outside the lock: never one whose callback still runs, and never under the lock
  // that callback takes.
  std::list<Timer> timers_;
};

}  // namespace dtmf::server
