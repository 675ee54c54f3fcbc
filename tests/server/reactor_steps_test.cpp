// How a gRPC reactor's steps run (reactor_steps.h): at the time named and not before, never two
// at once, none lost, and none after the reactor is gone.
#include "reactor_steps.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <thread>

using namespace std::chrono_literals;
using dtmf::server::ReactorSteps;
using Clock = std::chrono::steady_clock;

namespace {

// A reactor's stand-in: its steps, counted, and whether two ever overlapped.
struct Stepped {
  std::optional<ReactorSteps> steps;
  std::mutex mutex;
  std::condition_variable stepped;
  int count = 0;
  std::atomic<int> inside{0};
  std::atomic<bool> overlapped{false};
  std::vector<Clock::time_point> at;
  std::function<void()> during;  // what the first step does inside it

  static std::shared_ptr<Stepped> make() {
    auto s = std::make_shared<Stepped>();
    s->steps.emplace(std::weak_ptr<void>(s), [raw = s.get()] { raw->step(); });
    return s;
  }
  void step() {
    if (++inside > 1) overlapped = true;
    std::function<void()> first;
    {
      std::lock_guard lock(mutex);
      ++count;
      at.push_back(Clock::now());
      if (count == 1) first = during;
    }
    if (first) first();
    --inside;
    stepped.notify_all();
  }
  bool wait_for_count(int n, std::chrono::milliseconds limit) {
    std::unique_lock lock(mutex);
    return stepped.wait_for(lock, limit, [&] { return count >= n; });
  }
};

}  // namespace

TEST(ReactorSteps, AStepAtATimeRunsThenAndNotBefore) {
  auto s = Stepped::make();
  const auto asked = Clock::now();
  s->steps->run_at(asked + 80ms);
  ASSERT_TRUE(s->wait_for_count(1, 3s)) << "the alarm never stepped";
  EXPECT_GE(s->at.front() - asked, 79ms) << "it stepped before its time";
  // A later time while an earlier one is pending adds nothing: one step, not two.
  s->steps->run_at(Clock::now() + 50ms);
  s->steps->run_at(Clock::now() + 150ms);
  ASSERT_TRUE(s->wait_for_count(2, 3s));
  EXPECT_FALSE(s->wait_for_count(3, 300ms)) << "a time after a pending one made a step of its own";
}

TEST(ReactorSteps, AnInputDuringAStepMakesOneMoreStepAndNeverAnOverlap) {
  auto s = Stepped::make();
  // The first step's input comes from another thread while it runs: that thread returns at
  // once, and the step runs again after this one, on this thread.
  s->during = [&] {
    std::thread other([&] { s->steps->run(); });
    other.join();
    s->steps->run_soon();  // and one from the transmitter's side, to gRPC's threads
  };
  s->steps->run();
  EXPECT_EQ(s->count, 2) << "the input during the step was lost, or stepped inside it";
  ASSERT_TRUE(s->wait_for_count(3, 3s)) << "run_soon never stepped";
  EXPECT_FALSE(s->overlapped);
}

TEST(ReactorSteps, AnAlarmDueAfterItsReactorIsGoneStepsNothing) {
  auto s = Stepped::make();
  std::weak_ptr<Stepped> gone = s;
  std::atomic<int>* never = new std::atomic<int>(0);  // outlives the reactor, to be read after
  s->steps.reset();
  s->steps.emplace(std::weak_ptr<void>(s), [never] { ++*never; });
  s->steps->run_at(Clock::now() + 30ms);
  s.reset();
  ASSERT_TRUE(gone.expired());
  // Long past its time: the cancelled alarm found no reactor.
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(never->load(), 0);
  delete never;
}
