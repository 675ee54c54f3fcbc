// The counter state on disk fails closed (issue 34): a robot with no state for its key, or
// with state it cannot read in the exact form written, opens no store (so dtmf-agent does
// not start and nothing old is executed); --new-key (RobotKey::New) makes the state of a key
// just made and is refused for a key that has state; the state directory must be the user's
// own and no one else's to write; nothing is ever read or written through a planted symbolic
// link; and the lock is taken when the store opens.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "security/counter_file.h"
#include "security/freshness.h"
#include "support/temp_dir.h"

using namespace dtmf::security;
namespace fs = std::filesystem;

namespace {

// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-robot-state") {}
};

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
}

// The message of what `open` throws, or "" when it throws nothing.
template <typename F>
std::string refusal(F open) {
  try {
    open();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Every way a robot file can be other than "accepted N\n" as written: empty, cut short, an
// unknown field, no number, junk after it, and bytes of no text at all.
const std::vector<std::string> kDamagedRobotStates = {
    "",
    "accepted",
    "accepted\n",
    "accepted \n",
    "accepted x\n",
    "accepted 12 junk\n",
    "accepted 12\njunk\n",
    "accepted 12\naccepted 13\n",
    "accepted 12",  // cut short: no end of line
    "accepted 1",
    "garbage",
    "garbage\n",
    "reserved 12\n",  // the sender's field
    "Accepted 12\n",
    " accepted 12\n",
    "accepted  12\n",
    "accepted -1\n",
    "accepted +12\n",
    "accepted 012\n",
    "accepted 12\r\n",
    "accepted 0x10\n",
    "accepted 68719476736\n",  // 2^36: beyond the counter
    "accepted 99999999999999999999999999\n",
    std::string("\0\0\0\0", 4),
    std::string("\xff\xfe\x13\x00\x01 accepted 7\n", 18),
    std::string("accepted 7\n\0", 12),
};

}  // namespace

TEST(RobotState, AWipedStateDirectoryOrAMissingFileOpensNoRobot) {
  TempDir dir;
  const auto key = LinkKey::generate();
  // Wiped: the directory itself is gone.
  const std::string wiped = refusal([&] { FileCounterStore::open_robot(dir.path / "wiped", *key); });
  EXPECT_TRUE(has(wiped, "no counter state for key " + key->id_hex())) << wiped;
  EXPECT_TRUE(has(wiped, "start once with --new-key")) << wiped;
  EXPECT_TRUE(has(wiped, "make a new key (dtmfctl keygen)")) << wiped;
  // The directory is there, with another key's state in it.
  const auto other = LinkKey::generate();
  FileCounterStore::open_robot(dir.path, *other, RobotKey::New)->accept(50);
  const std::string missing = refusal([&] { FileCounterStore::open_robot(dir.path, *key); });
  EXPECT_TRUE(has(missing, "no counter state for key " + key->id_hex() + " in " + dir.path.string())) << missing;
  EXPECT_FALSE(fs::exists(dir.path / ("robot-" + key->id_hex()))) << "refusing writes nothing";
}

TEST(RobotState, EveryDamagedRobotFileIsRefusedAndLeftAsItWas) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const fs::path file = dir.path / ("robot-" + key->id_hex());
  for (const std::string& text : kDamagedRobotStates) {
    write_file(file, text);
    const std::string shown = ::testing::PrintToString(text);
    const std::string e = refusal([&] { FileCounterStore::open_robot(dir.path, *key); });
    EXPECT_TRUE(has(e, "the counter state " + file.string() + " is damaged: ")) << shown << ": " << e;
    EXPECT_TRUE(has(e, "The robot cannot tell which frames are old")) << shown << ": " << e;
    EXPECT_TRUE(has(e, "Make a new key (dtmfctl keygen), install it on both sides, and start dtmf-agent --new-key"))
        << shown << ": " << e;
    // --new-key is no way around it.
    EXPECT_TRUE(has(refusal([&] { FileCounterStore::open_robot(dir.path, *key, RobotKey::New); }), "is damaged"))
        << shown;
    EXPECT_EQ(read_file(file), text) << "left for the operator to see";
  }
  // What each damage is, in words.
  const auto why = [&](const std::string& text) {
    write_file(file, text);
    return refusal([&] { FileCounterStore::open_robot(dir.path, *key); });
  };
  EXPECT_TRUE(has(why(""), "is damaged: it is empty"));
  EXPECT_TRUE(has(why("accepted 12"), "is cut short"));
  EXPECT_TRUE(has(why("garbage\n"), "line 1 is 'garbage', where 'accepted <number>' belongs"));
  EXPECT_TRUE(has(why("accepted x\n"), "its value is not a decimal number"));
  EXPECT_TRUE(has(why("accepted 12 junk\n"), "its value is not a decimal number"));
  EXPECT_TRUE(has(why("accepted 12\njunk\n"), "it goes on after its last line: 'junk\\x0a'"));
  EXPECT_TRUE(has(why(std::string("\xff\x01\n", 3)), "line 1 is '\\xff\\x01'"));
  // Exactly what the store writes is read back.
  write_file(file, "accepted 0\n");
  EXPECT_EQ(FileCounterStore::open_robot(dir.path, *key)->last_accepted(), 0u);
  write_file(file, "accepted 68719476735\n");
  EXPECT_EQ(FileCounterStore::open_robot(dir.path, *key)->last_accepted(), kCounterLimit - 1);
}

TEST(RobotState, ADamagedSenderFileIsRefusedToo) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const fs::path file = dir.path / ("sender-" + key->id_hex());
  for (const std::string& text :
       {std::string(), std::string("reserved"), std::string("reserved x\n"), std::string("reserved 12 junk\n"),
        std::string("reserved 12"), std::string("reserved 12\nconfirmed\n"), std::string("reserved 12\nconfirmed 3"),
        std::string("reserved 12\nconfirmed 3\njunk\n"), std::string("confirmed 3\nreserved 12\n"),
        std::string("accepted 12\n"), std::string("garbage\n"), std::string("\x00\x01\x02", 3)}) {
    write_file(file, text);
    const std::string e = refusal([&] { FileCounterStore::open_sender(dir.path, *key); });
    EXPECT_TRUE(has(e, "the counter state " + file.string() + " is damaged: ")) << ::testing::PrintToString(text) << e;
    EXPECT_TRUE(has(e, "This sender cannot tell which counters it used")) << e;
    EXPECT_EQ(read_file(file), text);
  }
  write_file(file, "reserved 1000\nconfirmed 990\n");
  const auto store =
      FileCounterStore::open_sender(dir.path, *key, [] { return std::chrono::system_clock::time_point{}; });
  EXPECT_EQ(store->last_confirmed(), 990u);
  EXPECT_EQ(store->next_counter(), 1000u);
}

// A sender with no state is safe: it starts above the clock's floor (and so above anything an
// earlier sender used, at under 20 frames a second).
TEST(RobotState, ASenderWithNoStateStillStartsFromTheClock) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const auto now = std::chrono::system_clock::now();
  EXPECT_EQ(FileCounterStore::open_sender(dir.path / "new", *key, [&] { return now; })->next_counter(),
            clock_counter_floor(now));
}

TEST(RobotState, NewKeyWritesTheFreshStateOnceAndIsRefusedForAKeyUsedHere) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const fs::path state = dir.path / "state";
  const fs::path file = state / ("robot-" + key->id_hex());
  {
    const auto robot = FileCounterStore::open_robot(state, *key, RobotKey::New);
    EXPECT_EQ(read_file(file), "accepted 0\n") << "on disk before the robot listens";
    EXPECT_EQ(robot->last_accepted(), 0u);
    EXPECT_EQ(fs::status(file).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_EQ(fs::status(state).permissions() & fs::perms::all, fs::perms::owner_all);
  }
  // A second --new-key, even before anything was accepted: refused, the state kept.
  std::string e = refusal([&] { FileCounterStore::open_robot(state, *key, RobotKey::New); });
  EXPECT_TRUE(has(e, "key " + key->id_hex() + " has been used here (last accepted 0")) << e;
  EXPECT_TRUE(has(e, "drop --new-key")) << e;
  {
    const auto robot = FileCounterStore::open_robot(state, *key);
    robot->accept(500);
    EXPECT_EQ(read_file(file), "accepted 500\n");
  }
  e = refusal([&] { FileCounterStore::open_robot(state, *key, RobotKey::New); });
  EXPECT_TRUE(has(
      e, "key " + key->id_hex() + " has been used here (last accepted 500, in " + file.string() + "): drop --new-key"))
      << e;
  EXPECT_EQ(read_file(file), "accepted 500\n") << "--new-key cannot wipe a used key's state";
  EXPECT_EQ(FileCounterStore::open_robot(state, *key)->last_accepted(), 500u);
}

TEST(RobotState, EachRoleIsTheOnlyOneItsStoreServes) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const auto robot = FileCounterStore::open_robot(dir.path, *key, RobotKey::New);
  EXPECT_THROW(robot->next_counter(), std::logic_error);
  EXPECT_THROW(robot->confirmed(3), std::logic_error);
  const auto sender = FileCounterStore::open_sender(dir.path, *key);  // its own lock and file
  EXPECT_THROW(sender->accept(3), std::logic_error);
  EXPECT_THROW((void)sender->last_accepted(), std::logic_error);
  EXPECT_GT(sender->next_counter(), 0u);
}

// The lock is taken when the store opens, so a second robot (or sender) on the same state
// fails at its start, not at its first frame.
TEST(RobotState, TheLockIsTakenWhenTheStoreOpens) {
  TempDir dir;
  const auto key = LinkKey::generate();
  {
    const auto first = FileCounterStore::open_robot(dir.path, *key, RobotKey::New);
    const std::string e = refusal([&] { FileCounterStore::open_robot(dir.path, *key); });
    EXPECT_TRUE(has(e, "another process keeps its robot counter in " + dir.path.string())) << e;
  }
  EXPECT_NO_THROW(FileCounterStore::open_robot(dir.path, *key)) << "free once the first is gone";
  const auto sender = FileCounterStore::open_sender(dir.path, *key);
  const std::string e = refusal([&] { FileCounterStore::open_sender(dir.path, *key); });
  EXPECT_TRUE(has(e, "another process keeps its sender counter")) << e;
}

TEST(RobotState, AStateDirectoryOthersMayWriteOrThatIsAnotherUsersIsRefused) {
  TempDir dir;
  const auto key = LinkKey::generate();
  FileCounterStore::open_robot(dir.path, *key, RobotKey::New)->accept(9);
  for (const mode_t mode : {0770, 0730, 0707, 0777, 01777}) {
    ASSERT_EQ(::chmod(dir.path.c_str(), mode), 0);
    char octal[8];
    std::snprintf(octal, sizeof octal, "%04o", mode);
    for (const std::string& e : {refusal([&] { FileCounterStore::open_robot(dir.path, *key); }),
                                 refusal([&] { FileCounterStore::open_sender(dir.path, *key); })}) {
      EXPECT_TRUE(has(e, "the state directory " + dir.path.string() + " has mode " + octal)) << e;
      EXPECT_TRUE(has(e, "chmod 700 " + dir.path.string())) << e;
    }
  }
  for (const mode_t mode : {0700, 0750, 0755}) {
    ASSERT_EQ(::chmod(dir.path.c_str(), mode), 0);
    EXPECT_EQ(FileCounterStore::open_robot(dir.path, *key)->last_accepted(), 9u) << std::oct << mode;
  }
  // Another user's directory.
  std::string e;
  if (::geteuid() == 0) {
    ASSERT_EQ(::chown(dir.path.c_str(), 65534, 65534), 0);
    e = refusal([&] { FileCounterStore::open_robot(dir.path, *key); });
    EXPECT_TRUE(has(e, "the state directory " + dir.path.string() + " belongs to user 65534, not to this one (0)"))
        << e;
    ASSERT_EQ(::chown(dir.path.c_str(), 0, 0), 0);
  } else {
    e = refusal([&] { FileCounterStore::open_robot("/", *key); });
    EXPECT_TRUE(has(e, "the state directory / belongs to user 0")) << e;
  }
  EXPECT_TRUE(has(e, "chmod 700")) << e;
  // A link to the directory is the operator's (systemd's StateDirectory= with DynamicUser= is one).
  fs::create_directory_symlink(dir.path, dir.path.string() + "-link");
  EXPECT_EQ(FileCounterStore::open_robot(dir.path.string() + "-link", *key)->last_accepted(), 9u);
  fs::remove(dir.path.string() + "-link");
}

// A symbolic link planted where the store writes its temporary, or as the state or lock
// file itself: never followed, its target never written.
TEST(RobotState, ALinkPlantedInTheStateDirectoryIsNeverWrittenThrough) {
  TempDir dir;
  const auto key = LinkKey::generate();
  const fs::path state = dir.path / "state", victim = dir.path / "victim";
  const std::string id = key->id_hex();
  write_file(victim, "precious\n");
  const auto plant = [&](const std::string& name, const fs::path& target) {
    fs::remove(state / name);
    fs::create_symlink(target, state / name);
  };
  fs::create_directory(state, dir.path);
  fs::permissions(state, fs::perms::owner_all);

  // The robot's temporary: at --new-key, and at every accepted frame.
  plant("robot-" + id + ".new", victim);
  auto robot = FileCounterStore::open_robot(state, *key, RobotKey::New);
  EXPECT_EQ(read_file(victim), "precious\n");
  plant("robot-" + id + ".new", victim);
  robot->accept(77);
  EXPECT_EQ(read_file(victim), "precious\n");
  EXPECT_EQ(read_file(state / ("robot-" + id)), "accepted 77\n");
  EXPECT_FALSE(fs::is_symlink(state / ("robot-" + id)));
  // A dangling link: its target is not made.
  plant("robot-" + id + ".new", dir.path / "made");
  robot->accept(78);
  EXPECT_FALSE(fs::exists(dir.path / "made"));
  robot.reset();

  // The sender's temporary, at a reservation and at exit.
  plant("sender-" + id + ".new", victim);
  {
    const auto sender = FileCounterStore::open_sender(state, *key);
    sender->confirmed(sender->next_counter());
    EXPECT_EQ(read_file(victim), "precious\n");
    plant("sender-" + id + ".new", victim);
  }
  EXPECT_EQ(read_file(victim), "precious\n");
  EXPECT_TRUE(has(read_file(state / ("sender-" + id)), "confirmed "));

  // The state file itself a link (to a file that reads as fresh state): refused, not read.
  write_file(dir.path / "old", "accepted 1\n");
  plant("robot-" + id, dir.path / "old");
  std::string e = refusal([&] { FileCounterStore::open_robot(state, *key); });
  EXPECT_TRUE(has(e, "is damaged: it is a symbolic link")) << e;
  plant("sender-" + id, victim);
  e = refusal([&] { FileCounterStore::open_sender(state, *key); });
  EXPECT_TRUE(has(e, "is damaged: it is a symbolic link")) << e;
  // Not a regular file.
  fs::remove(state / ("robot-" + id));
  ASSERT_EQ(::mkfifo((state / ("robot-" + id)).c_str(), 0600), 0);
  e = refusal([&] { FileCounterStore::open_robot(state, *key); });
  EXPECT_TRUE(has(e, "is damaged: it is not a regular file")) << e;
  // The lock file a link: refused, its target neither made nor changed.
  plant("robot-" + id + ".lock", victim);
  EXPECT_FALSE(refusal([&] { FileCounterStore::open_robot(state, *key); }).empty());
  plant("robot-" + id + ".lock", dir.path / "lock-made");
  EXPECT_FALSE(refusal([&] { FileCounterStore::open_robot(state, *key); }).empty());
  EXPECT_FALSE(fs::exists(dir.path / "lock-made"));
  EXPECT_EQ(read_file(victim), "precious\n");
}
