// dtmf-server --robots FILE: the robots file read, and every mistake in it named.
#include "robot_roster.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "secret_file.h"
#include "security/link_key.h"
#include "shown_text.h"

using dtmf::server::parse_robots;
using dtmf::server::shown;
namespace fs = std::filesystem;

TEST(RobotRoster, ReadsEachRobotsNameAddressKeyAndModel) {
  const auto robots = parse_robots(R"([{"name": "alpha", "address": 1, "key": "/k/alpha.key", "model": "waffle"},
                                       {"name": "beta-2", "address": 7}])",
                                   "robots.json");
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0].name, "alpha");
  EXPECT_EQ(robots[0].address, 1);
  EXPECT_EQ(robots[0].key_file, "/k/alpha.key");
  EXPECT_EQ(robots[0].model, "waffle");
  EXPECT_EQ(robots[1].name, "beta-2");
  EXPECT_EQ(robots[1].address, 7);
  EXPECT_EQ(robots[1].key_file, "");
  EXPECT_EQ(robots[1].model, "burger");
}

TEST(RobotRoster, EveryMistakeIsNamedWithTheFileTheRobotAndTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {"not json", "not JSON"},
      {R"({"name": "alpha"})", "not a list"},
      {"[]", "lists no robot"},
      {R"([{"address": 1}])", "robot 1: \"name\" is required"},
      {R"([{"name": "al pha", "address": 1}])", "name \"al pha\""},
      {R"([{"name": "alpha"}])", "robot 1 \"alpha\": \"address\" is required"},
      {R"([{"name": "alpha", "address": 8}])", "address 8 is outside 0..7"},
      {R"([{"name": "alpha", "address": -1}])", "address -1 is outside 0..7"},
      {R"([{"name": "alpha", "address": 1.5}])", "\"address\" is required, a whole number"},
      {R"([{"name": "alpha", "address": 1, "model": "tank"}])", "model \"tank\" is none of burger, waffle"},
      {R"([{"name": "alpha", "address": 1, "key": ""}])", "\"key\" is the path"},
      {R"([{"name": "alpha", "address": 1, "adress": 2}])", "unknown field \"adress\""},
      {R"([{"name": "a", "address": 1}, {"name": "a", "address": 2}])", "two robots are called \"a\""},
      {R"([{"name": "a", "address": 1}, {"name": "b", "address": 1}])", "robots \"a\" and \"b\" share address 1"},
  };
  for (const auto& [json, expected] : cases) {
    try {
      parse_robots(json, "robots.json");
      ADD_FAILURE() << "accepted " << json;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("robots.json", 0), 0u) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << json << " -> " << what;
    }
  }
}

// Issue 59: names, unknown field names and models were echoed raw into the error: a newline
// forged a log line, ANSI escapes reached the terminal, a 100 kB name was printed whole. Each
// is shown quoted, with control characters escaped, and cut at 64 bytes; a key path holding a
// control character is refused the same way.
TEST(RobotRoster, TextFromTheFileIsShownQuotedEscapedAndCut) {
  const std::string long_name(100000, 'n');
  const std::pair<std::string, std::string> cases[] = {
      {R"([{"name": "al\npha", "address": 1}])", R"(name "al\npha")"},
      {R"([{"name": "\u001b[2J\u001b[31mred", "address": 1}])", R"(name "\x1b[2J\x1b[31mred")"},
      {"[{\"name\": \"" + long_name + "\", \"address\": 1}]",
       "name \"" + std::string(64, 'n') + "\"... (100000 bytes, first 64 shown)"},
      {R"([{"name": "alpha", "address": 1, "ad\ndress\u001b": 2}])", R"(unknown field "ad\ndress\x1b")"},
      {"[{\"name\": \"alpha\", \"address\": 1, \"" + long_name + "\": 2}]",
       "unknown field \"" + std::string(64, 'n') + "\"... (100000 bytes, first 64 shown)"},
      {R"([{"name": "alpha", "address": 1, "model": "tank\n[info] forged"}])", R"(model "tank\n[info] forged")"},
      {R"([{"name": "alpha", "address": 1, "key": "/k/a\r\n.key"}])", R"(key "/k/a\r\n.key")"},
  };
  for (const auto& [json, expected] : cases) {
    try {
      parse_robots(json, "robots.json");
      ADD_FAILURE() << "accepted " << json.substr(0, 200);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(expected), std::string::npos) << what.substr(0, 300);
      EXPECT_EQ(what.find_first_of("\n\r\x1b"), std::string::npos) << what.substr(0, 300);
      EXPECT_LT(what.size(), 300u) << what.substr(0, 300);
    }
  }
}

TEST(ShownText, QuotesEscapesEveryByteOutsidePrintableAsciiAndCutsAt64) {
  EXPECT_EQ(shown("alpha"), R"("alpha")");
  EXPECT_EQ(shown("a\"b\\c"), R"("a\"b\\c")");
  EXPECT_EQ(shown("a\nb\r\tc\x1b[0m\x7f"), R"("a\nb\r\tc\x1b[0m\x7f")");
  EXPECT_EQ(shown(std::string("a\0b", 3)), R"("a\x00b")");
  const std::string utf8 =
      "K\xc3\xbc"
      "che \xe2\x80\xae";  // "Küche" and a right-to-left override
  EXPECT_EQ(shown(utf8), R"("K\xc3\xbcche \xe2\x80\xae")");
  EXPECT_EQ(shown(std::string(64, 'x')), "\"" + std::string(64, 'x') + "\"");
  EXPECT_EQ(shown(std::string(65, 'x')), "\"" + std::string(64, 'x') + "\"... (65 bytes, first 64 shown)");
  // The longest anything can be shown: 64 bytes of \xNN, and the cut.
  const std::string worst = shown(std::string(3'000'000, '\x1b'));
  EXPECT_EQ(worst.size(), 2 + 64 * 4 + std::string("... (3000000 bytes, first 64 shown)").size()) << worst;
}

namespace {

// A directory of its own for a test, removed after it.
struct TempDir {
  fs::path path = fs::path(::testing::TempDir()) / ("roster-" + std::to_string(::getpid()) + "-" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name, const std::string& text, mode_t mode) const {
    const fs::path p = path / name;
    std::ofstream(p) << text;
    ::chmod(p.c_str(), mode);
    return p.string();
  }
};

std::string refusal_of(const std::string& file) {
  try {
    dtmf::server::read_robots(file);
  } catch (const dtmf::server::SecretFileError& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST(RobotsFile, IsReadOnlyIfNoOneElseMayChangeItAndNotThroughALink) {
  const TempDir dir;
  const std::string json = R"([{"name": "alpha", "address": 1}])";
  EXPECT_EQ(dtmf::server::read_robots(dir.file("ok.json", json, 0644)).at(0).name, "alpha");
  EXPECT_EQ(dtmf::server::read_robots(dir.file("own.json", json, 0600)).at(0).name, "alpha");
  const std::string writable = dir.file("writable.json", json, 0664);
  EXPECT_NE(refusal_of(writable).find("may be changed by others (mode 0664)"), std::string::npos)
      << refusal_of(writable);
  EXPECT_NE(refusal_of(writable).find("chmod go-w " + writable), std::string::npos) << refusal_of(writable);
  const fs::path link = dir.path / "link.json";
  fs::create_symlink(dir.path / "ok.json", link);
  EXPECT_NE(refusal_of(link).find("is a symbolic link"), std::string::npos) << refusal_of(link);
  EXPECT_NE(refusal_of(link).find("--robots " + (dir.path / "ok.json").string()), std::string::npos)
      << refusal_of(link);
  // A FIFO is refused at once, not waited on for a writer.
  const fs::path fifo = dir.path / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(refusal_of(fifo).find("is not a regular file"), std::string::npos) << refusal_of(fifo);
  if (::geteuid() == 0) {  // only root can give a file away
    const std::string theirs = dir.file("theirs.json", json, 0644);
    ASSERT_EQ(::chown(theirs.c_str(), 4242, 4242), 0);
    EXPECT_NE(refusal_of(theirs).find("belongs to user 4242"), std::string::npos) << refusal_of(theirs);
    EXPECT_NE(refusal_of(theirs).find("chown 0 " + theirs), std::string::npos) << refusal_of(theirs);
  }
}

TEST(RobotRoster, TwoRobotsUnderOneKeyOrARobotUnderTheRoomKeyAreRefusedNamingBoth) {
  const TempDir dir;
  const auto a = dtmf::security::LinkKey::generate(), b = dtmf::security::LinkKey::generate();
  const std::string a_file = (dir.path / "a.key").string(), a_copy = (dir.path / "a-copy.key").string(),
                    b_file = (dir.path / "b.key").string();
  a->save(a_file);
  a->save(a_copy);
  b->save(b_file);
  using Entries = std::vector<dtmf::server::RobotEntry>;
  const auto refusal = [](const Entries& robots, const std::string& room) {
    try {
      dtmf::server::check_keys_apart(robots, room, "robots.json");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const Entries apart = {{"alpha", 1, a_file}, {"beta", 2, b_file}, {"gamma", 3, ""}, {"delta", 4, ""}};
  EXPECT_EQ(refusal(apart, ""), "(accepted)");  // robots without a key share nothing
  const Entries one_file = {{"alpha", 1, a_file}, {"beta", 2, b_file}, {"gamma", 3, a_file}};
  const Entries one_key = {{"alpha", 1, a_file}, {"beta", 2, a_copy}};
  for (const Entries& robots : {one_file, one_key}) {
    const std::string said = refusal(robots, "");
    const std::string expected =
        "robots.json: robots \"alpha\" and \"" + robots.back().name + "\" have one key (key id " + a->id_hex();
    EXPECT_EQ(said.rfind(expected, 0), 0u) << said;
    EXPECT_NE(said.find("dtmfctl keygen"), std::string::npos) << said;
  }
  const std::string room = refusal(apart, b_file);
  EXPECT_EQ(room.rfind("robots.json: robot \"beta\" has the room key as its own (key id " + b->id_hex(), 0), 0u)
      << room;
  EXPECT_NE(room.find("any of them could drive \"beta\""), std::string::npos) << room;
}
