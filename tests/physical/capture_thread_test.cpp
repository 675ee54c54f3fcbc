// physical/capture_thread.h: a microphone drained by a raised thread of its own, handed to a
// reader at normal priority. The device here is a stand-in that counts samples (a fake is
// fine inside one layer's unit test); tests/physical/portaudio_air_test.cpp opens real ones.
#include "physical/capture_thread.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <future>
#include <thread>

#include "physical/realtime_priority.h"

namespace dtmf::physical {
namespace {

constexpr int kRateHz = 48000;

struct Scheduling {
  int policy = SCHED_OTHER;
  int nice = 0;
  bool operator==(const Scheduling&) const = default;
};

Scheduling this_thread_scheduling() {
  Scheduling s;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &s.policy, &param);
  s.nice = ::getpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)));
  return s;
}

// Samples 0, 1, 2, ... up to `total`, then the end, or `failure` instead of the end.
class CountingDevice : public AudioSource {
 public:
  CountingDevice(std::size_t total, std::string failure = {}) : total_(total), failure_(std::move(failure)) {}
  std::size_t read(std::span<float> out) override {
    if (next_ == 0) {
      reader_ = std::this_thread::get_id();
      scheduling_ = this_thread_scheduling();
    }
    const std::size_t n = std::min(out.size(), total_ - next_);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(next_++);
    if (n == 0) {
      exhausted_.set_value();
      if (!failure_.empty()) throw AudioError(failure_);
    }
    return n;
  }
  int sample_rate_hz() const override { return kRateHz; }
  std::string describe() const override { return "counting device"; }

  std::thread::id reader_;
  Scheduling scheduling_;
  std::promise<void> exhausted_;

 private:
  std::size_t total_;
  std::string failure_;
  std::size_t next_ = 0;
};

std::vector<float> read_all(AudioSource& source, std::size_t block) {
  std::vector<float> all, buffer(block);
  while (const std::size_t got = source.read(buffer)) all.insert(all.end(), buffer.begin(), buffer.begin() + got);
  return all;
}

TEST(CaptureThread, HandsOverEverySampleInOrderThenTheEnd) {
  auto device = std::make_unique<CountingDevice>(10'007);
  CaptureThread capture(std::move(device));
  EXPECT_EQ(capture.sample_rate_hz(), kRateHz);
  EXPECT_EQ(capture.describe(), "counting device");
  // Blocks that are no multiple of the chunk the thread reads, and a partial last one.
  const std::vector<float> all = read_all(capture, 1000);
  ASSERT_EQ(all.size(), 10'007u);
  for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i], static_cast<float>(i)) << i;
  EXPECT_EQ(capture.dropped_samples(), 0);
}

TEST(CaptureThread, TheDevicesFailureReachesTheReaderAfterTheSamplesBeforeIt) {
  CaptureThread capture(std::make_unique<CountingDevice>(2000, "the microphone was unplugged"));
  std::vector<float> block(500);
  for (int i = 0; i < 4; ++i) ASSERT_EQ(capture.read(block), 500u);
  EXPECT_EQ(block.back(), 1999.0f);
  try {
    capture.read(block);
    FAIL() << "the failure was not handed over";
  } catch (const AudioError& e) {
    EXPECT_STREQ(e.what(), "the microphone was unplugged");
  }
}

TEST(CaptureThread, AReaderFarBehindLosesTheNewestSamplesAndTheyAreCounted) {
  const auto chunk = static_cast<std::size_t>(kCaptureChunkMs * kRateHz / 1000);  // 480
  auto device = std::make_unique<CountingDevice>(40 * chunk);
  std::future<void> exhausted = device->exhausted_.get_future();
  CaptureThread capture(std::move(device), /*capacity_ms=*/100);  // 4800 samples, 10 chunks
  exhausted.wait();  // the whole device was read while nobody took anything
  EXPECT_DOUBLE_EQ(capture.queued_ms(), 100.0);
  EXPECT_EQ(capture.dropped_samples(), static_cast<long long>(30 * chunk));
  // The oldest are kept: a decoder behind hears what came first, with a gap after it.
  const std::vector<float> kept = read_all(capture, 1000);
  ASSERT_EQ(kept.size(), 10 * chunk);
  EXPECT_EQ(kept.front(), 0.0f);
  EXPECT_EQ(kept.back(), static_cast<float>(10 * chunk - 1));
}

TEST(CaptureThread, TheDeviceIsReadInARaisedThreadAndTheReaderKeepsItsPriority) {
  // What this machine lets an audio thread have: real time, a nice level, or (unprivileged,
  // no rtprio limit) nothing, where only the thread itself is checked.
  Scheduling raised;
  std::thread([&] {
    raise_capture_thread_priority();
    raised = this_thread_scheduling();
  }).join();
  const Scheduling mine = this_thread_scheduling();

  auto device = std::make_unique<CountingDevice>(4800);
  CountingDevice& seen = *device;
  CaptureThread capture(std::move(device));
  read_all(capture, 480);
  EXPECT_NE(seen.reader_, std::this_thread::get_id());
  EXPECT_EQ(seen.scheduling_, raised);
  EXPECT_EQ(this_thread_scheduling(), mine);
}

}  // namespace
}  // namespace dtmf::physical
