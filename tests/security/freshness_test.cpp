// Freshness: which counter a frame's low bits stand for, and the counters kept on disk across
// restarts — never a value twice, whatever the process went through.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <set>

#include "security/counter_file.h"
#include "security/freshness.h"
#include "support/temp_dir.h"

using namespace dtmf::security;
namespace fs = std::filesystem;

namespace {
constexpr std::uint64_t kNow = 2000;  // the robot's clock as a counter
}  // namespace

TEST(Freshness, LowBitsCompleteToTheWindowAfterTheLastAccepted) {
  EXPECT_EQ(complete_counter(1000, counter_low_bits(1000)), 1000u) << "the last frame again";
  EXPECT_EQ(complete_counter(1000, counter_low_bits(1001)), 1001u);
  EXPECT_EQ(complete_counter(1000, counter_low_bits(1511)), 1511u) << "the window's far end";
  EXPECT_EQ(complete_counter(1000, counter_low_bits(1512)), 1000u) << "a window on: read as the last frame";
  EXPECT_EQ(complete_counter(1000, counter_low_bits(999)), 1511u) << "an older frame completes to a newer counter";
  EXPECT_EQ(freshness_of(1000, 1000, kNow), Freshness::Repeat);
  EXPECT_EQ(freshness_of(1000, 1001, kNow), Freshness::New);
  EXPECT_EQ(freshness_of(1000, 999, kNow), Freshness::Stale);
  EXPECT_EQ(freshness_of(0, 0, kNow), Freshness::Stale);
  EXPECT_EQ(freshness_of(1000, kNow + kClockMargin, kNow), Freshness::New) << "the margin's end";
  EXPECT_EQ(freshness_of(1000, kNow + kClockMargin + 1, kNow), Freshness::Ahead) << "past the robot's clock";
  EXPECT_EQ(freshness_of(kNow + 2 * kClockMargin, kNow + 2 * kClockMargin, kNow), Freshness::Ahead)
      << "ahead comes first, even where the last accepted lies ahead too";
}

TEST(Freshness, TheSenderSynchronisesWhenTheRobotCouldNotComplete) {
  EXPECT_FALSE(completable(std::nullopt, 5)) << "nothing confirmed on record";
  EXPECT_TRUE(completable(100, 101));
  EXPECT_TRUE(completable(100, 100 + kCounterWindow - 1));
  EXPECT_FALSE(completable(100, 100 + kCounterWindow));
  EXPECT_FALSE(completable(100, 100));
}

namespace {
// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-state") {}
};

std::chrono::system_clock::time_point at(double seconds_since_2026) {
  return std::chrono::system_clock::time_point(std::chrono::seconds(1767225600)) +
         std::chrono::duration_cast<std::chrono::system_clock::duration>(
             std::chrono::duration<double>(seconds_since_2026));
}
}  // namespace

TEST(CounterFile, ASenderRestartedContinuesPastItsReservationAndAboveTheClock) {
  TempDir dir;
  const auto key = LinkKey::generate();
  std::uint64_t last = 0;
  {
    const auto store = FileCounterStore::open_sender(dir.path, *key, [] { return at(100); });
    const std::uint64_t first = store->next_counter();
    EXPECT_EQ(first, clock_counter_floor(at(100)));
    EXPECT_EQ(first, 1u + 100 * kCountersPerSecond);
    for (int i = 0; i < 40; ++i) last = store->next_counter();
    store->confirmed(last);
  }
  {
    // The clock went back: the reservation on disk still wins.
    const auto store = FileCounterStore::open_sender(dir.path, *key, [] { return at(50); });
    const std::uint64_t next = store->next_counter();
    EXPECT_GT(next, last);
    EXPECT_LE(next, last + kSenderBlock + 1);
    EXPECT_EQ(store->last_confirmed(), last) << "written with the reservation";
  }
  {
    // A day later the clock is far ahead of the reservation.
    const auto store = FileCounterStore::open_sender(dir.path, *key, [] { return at(86400); });
    EXPECT_EQ(store->next_counter(), clock_counter_floor(at(86400)));
  }
}

TEST(CounterFile, TheRobotsAcceptedCounterSurvivesARestartAndNeverGoesBack) {
  TempDir dir;
  const auto key = LinkKey::generate(), other = LinkKey::generate();
  {
    const auto store = FileCounterStore::open_robot(dir.path, *key, RobotKey::New);
    EXPECT_EQ(store->last_accepted(), 0u);
    store->accept(500);
    store->accept(400);
    EXPECT_EQ(store->last_accepted(), 500u);
  }
  EXPECT_EQ(FileCounterStore::open_robot(dir.path, *key)->last_accepted(), 500u);
  EXPECT_EQ(FileCounterStore::open_robot(dir.path / "x", *other, RobotKey::New)->last_accepted(), 0u)
      << "each key has its own counters";
}

// At its start, not at its first counter (tests/security/robot_state_test.cpp: the robot's).
TEST(CounterFile, ASecondProcessOnTheSameStateIsRefused) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const auto first = FileCounterStore::open_sender(dir.path, *key);
  try {
    FileCounterStore::open_sender(dir.path, *key);
    FAIL() << "two senders on one counter";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--state-dir"), std::string::npos) << e.what();
  }
}

TEST(CounterFile, AnUnwritableDirectorySaysWhatToDo) {
  const auto key = LinkKey::generate();
  if (::geteuid() == 0) {
    // root may write anywhere: a path below a regular file is unusable for anyone.
    try {
      FileCounterStore::open_sender("/etc/hostname/state", *key);
      FAIL();
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("--state-dir"), std::string::npos) << e.what();
    }
    return;
  }
  try {
    FileCounterStore::open_sender("/proc/dtmf-state", *key);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--state-dir"), std::string::npos) << e.what();
  }
}

// A sender killed with -9 at random moments, 20 times: every counter any of its lives handed
// out is new.
TEST(CounterFile, KilledTwentyTimesASenderNeverHandsOutACounterTwice) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const fs::path log = dir.path / "handed-out";
  std::set<std::uint64_t> seen;
  for (int life = 0; life < 20; ++life) {
    int pipe_fd[2];
    ASSERT_EQ(::pipe(pipe_fd), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(pipe_fd[0]);
      const auto store = FileCounterStore::open_sender(dir.path / "state", *key, [] { return at(0); });
      while (true) {
        const std::uint64_t c = store->next_counter();
        if (::write(pipe_fd[1], &c, sizeof c) != sizeof c) ::_exit(1);
      }
    }
    ::close(pipe_fd[1]);
    std::uint64_t c = 0;
    int read_count = 0;
    const int stop_after = 10 + life * 7;  // different moments in the block
    while (read_count < stop_after && ::read(pipe_fd[0], &c, sizeof c) == sizeof c) {
      EXPECT_TRUE(seen.insert(c).second) << "counter " << c << " handed out twice (life " << life << ")";
      ++read_count;
    }
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    while (::read(pipe_fd[0], &c, sizeof c) == sizeof c) {
      EXPECT_TRUE(seen.insert(c).second) << "counter " << c << " handed out twice (life " << life << ")";
    }
    ::close(pipe_fd[0]);
  }
  EXPECT_GT(seen.size(), 200u);
}
