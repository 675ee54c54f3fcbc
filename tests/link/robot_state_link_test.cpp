// A robot that lost its counter state, with its key kept (issue 34): an old recording — a
// synchronisation frame and commands made earlier under the key — executes nothing, whether
// the state directory was wiped or the state file is empty or garbled, because the robot's
// store refuses to open and so no receiver can be made. A key declared new (--new-key) runs
// it; the same robot after that refuses it again.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "command/command.h"
#include "link/link.h"
#include "security/counter_file.h"
#include "support/temp_dir.h"

using namespace dtmf;
namespace fs = std::filesystem;

namespace {

const LinkProfile& p = fast_profile();

// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-lost-state") {}
};

std::shared_ptr<const security::LinkKey> fixed_key() {
  std::array<unsigned char, security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(91 + 5 * i);
  return security::LinkKey::from_bytes(bytes);
}

link::LinkOptions keyed(std::shared_ptr<const security::LinkKey> key,
                        std::shared_ptr<security::CounterStore> counters) {
  link::LinkOptions o;
  o.key = std::move(key);
  o.counters = std::move(counters);
  return o;
}

// A session recorded off the air, made earlier under the key: a synchronisation frame, then
// the commands.
std::vector<float> old_recording(const std::shared_ptr<const security::LinkKey>& key) {
  const auto sender = link::make_link(p, keyed(key, std::make_shared<security::MemoryCounterStore>(40000)));
  std::vector<link::TransmitFrame> frames;
  for (const command::Command& c : {command::Command{command::DriveForward{60}}, command::Command{command::Turn{-40}},
                                    command::Command{command::DriveForDuration{80, 3}}}) {
    for (auto& f : sender->plan(c)) {
      sender->confirmed(f);
      frames.push_back(std::move(f));
    }
  }
  EXPECT_TRUE(frames.front().synchronisation);
  auto audio = sender->render(frames);
  audio.resize(audio.size() + 48000, 0.0f);
  return audio;
}

struct Outcome {
  bool started = false;  // the robot's store opened
  std::string refusal;   // why not
  int executed = 0;
};

// A robot started on `state` as dtmf-agent starts it (link options first, then a receiver),
// hearing `audio`.
Outcome robot_hears(const fs::path& state, const std::shared_ptr<const security::LinkKey>& key,
                    const std::vector<float>& audio, security::RobotKey start = security::RobotKey::Paired) {
  Outcome o;
  std::shared_ptr<security::CounterStore> store;
  try {
    store = security::FileCounterStore::open_robot(state, *key, start);
  } catch (const std::runtime_error& e) {
    o.refusal = e.what();
    return o;
  }
  o.started = true;
  const auto robot = link::make_link(p, keyed(key, store));
  const auto receiver = robot->receiver();
  for (std::size_t at = 0; at < audio.size(); at += 1024) {
    for (const auto& r :
         receiver->feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(1024, audio.size() - at)))) {
      o.executed += r.command ? 1 : 0;
    }
  }
  return o;
}

}  // namespace

TEST(RobotStateLink, AnOldRecordingExecutesNothingOnARobotThatLostItsState) {
  TempDir dir;
  const auto key = fixed_key();
  const auto recording = old_recording(key);
  const fs::path state = dir.path / "state";
  const fs::path file = state / ("robot-" + key->id_hex());

  // The robot as it was: paired with the key, it ran the session and refuses it again.
  const Outcome first = robot_hears(state, key, recording, security::RobotKey::New);
  ASSERT_TRUE(first.started) << first.refusal;
  EXPECT_EQ(first.executed, 3) << "the recording is a good one";
  const Outcome again = robot_hears(state, key, recording);
  ASSERT_TRUE(again.started) << again.refusal;
  EXPECT_EQ(again.executed, 0);

  // The state lost, each way: the robot does not start, so nothing executes.
  struct Loss {
    std::string name;
    std::optional<std::string> file_text;  // nothing: the directory wiped
  };
  for (const Loss& loss : {Loss{"wiped", std::nullopt}, Loss{"empty", ""}, Loss{"'accepted'", "accepted"},
                           Loss{"'accepted x'", "accepted x\n"}, Loss{"'accepted 12 junk'", "accepted 12 junk\n"},
                           Loss{"'garbage'", "garbage\n"}, Loss{"binary", std::string("\x00\xff\x7f\x80\n", 5)}}) {
    fs::remove_all(state);
    if (loss.file_text) {
      fs::create_directory(state);
      fs::permissions(state, fs::perms::owner_all);
      std::ofstream(file, std::ios::binary) << *loss.file_text;
    }
    const Outcome o = robot_hears(state, key, recording);
    EXPECT_FALSE(o.started) << loss.name;
    EXPECT_EQ(o.executed, 0) << loss.name;
    EXPECT_NE(o.refusal.find(loss.file_text ? "is damaged" : "no counter state for key"), std::string::npos)
        << loss.name << ": " << o.refusal;
    EXPECT_NE(o.refusal.find("--new-key"), std::string::npos) << loss.name << ": " << o.refusal;
  }
}
