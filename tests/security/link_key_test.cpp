// The security layer's key file: made with mode 0600, read back, refused when others may read
// it or when it is damaged, and never quoted in an error.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "security/frame_mac.h"
#include "security/link_key.h"

using namespace dtmf::security;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    char name[] = "/tmp/dtmf-key-XXXXXX";
    path = ::mkdtemp(name);
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string key_line(const std::string& text) {
  const auto at = text.find("\nkey ");
  return text.substr(at + 5, 64);
}

}  // namespace

TEST(LinkKey, SavedWithMode0600AndReadBackTheSame) {
  TempDir dir;
  const auto key = LinkKey::generate();
  key->save(dir.path / "k");
  struct stat info {};
  ASSERT_EQ(::stat((dir.path / "k").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  const auto back = LinkKey::load(dir.path / "k");
  EXPECT_EQ(back->id(), key->id());
  EXPECT_TRUE(std::equal(back->bytes().begin(), back->bytes().end(), key->bytes().begin()));
  EXPECT_NE(read_all(dir.path / "k").find("key-id " + key->id_hex()), std::string::npos);
}

TEST(LinkKey, TwoKeysDifferAndAKeyIsNeverOverwritten) {
  TempDir dir;
  const auto a = LinkKey::generate(), b = LinkKey::generate();
  EXPECT_NE(a->id(), b->id());
  a->save(dir.path / "k");
  try {
    b->save(dir.path / "k");
    FAIL() << "overwrote a key";
  } catch (const KeyFileError& e) {
    EXPECT_NE(std::string(e.what()).find("never overwritten"), std::string::npos) << e.what();
  }
  EXPECT_EQ(LinkKey::load(dir.path / "k")->id(), a->id());
}

TEST(LinkKey, AFileOthersMayReadIsRefusedWithTheChmodThatFixesIt) {
  TempDir dir;
  const fs::path file = dir.path / "k";
  LinkKey::generate()->save(file);
  const std::string secret = key_line(read_all(file));
  for (mode_t mode : {0640u, 0604u, 0660u, 0620u}) {
    ::chmod(file.c_str(), mode);
    try {
      LinkKey::load(file);
      FAIL() << "mode " << std::oct << mode << " accepted";
    } catch (const KeyFileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("chmod 600 " + file.string()), std::string::npos) << what;
      EXPECT_EQ(what.find(secret), std::string::npos);
    }
  }
  ::chmod(file.c_str(), 0400);
  EXPECT_NO_THROW(LinkKey::load(file));
}

TEST(LinkKey, ADamagedFileIsRefusedWithoutQuotingTheKey) {
  TempDir dir;
  const fs::path file = dir.path / "k";
  LinkKey::generate()->save(file);
  const std::string text = read_all(file);
  const std::string secret = key_line(text);
  const auto write = [&](const std::string& t) {
    fs::remove(file);
    std::ofstream(file) << t;
    ::chmod(file.c_str(), 0600);
  };
  std::string flipped = text;
  flipped[flipped.find("\nkey ") + 7] ^= 1;  // one digit of the key changed: the id no longer matches
  std::string short_key = text;
  short_key.erase(short_key.find("\nkey ") + 10, 2);
  for (const std::string& bad : {flipped, short_key, std::string("key-id 00000000\n"), std::string("hello world\n")}) {
    write(bad);
    try {
      LinkKey::load(file);
      FAIL() << "accepted: " << bad;
    } catch (const KeyFileError& e) {
      EXPECT_EQ(std::string(e.what()).find(secret), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find(secret.substr(0, 16)), std::string::npos) << e.what();
    }
  }
  fs::remove(file);
  try {
    LinkKey::load(file);
    FAIL();
  } catch (const KeyFileError& e) {
    EXPECT_NE(std::string(e.what()).find("dtmfctl keygen"), std::string::npos) << e.what();
  }
}

// The MAC covers every field it names: change any one and it changes. The answer's tag is
// not the frame's MAC, nor another key's.
TEST(FrameMac, EveryFieldAndTheKeyChangeIt) {
  const auto key = LinkKey::generate(), other = LinkKey::generate();
  const FrameMacInput in{3, 0, 123456789, 0x5ABCDEF};
  const std::uint32_t mac = frame_mac(*key, in);
  EXPECT_EQ(frame_mac(*key, in), mac) << "deterministic";
  EXPECT_NE(frame_mac(*other, in), mac);
  EXPECT_NE(frame_mac(*key, {4, 0, 123456789, 0x5ABCDEF}), mac);
  EXPECT_NE(frame_mac(*key, {3, 1, 123456789, 0x5ABCDEF}), mac);
  EXPECT_NE(frame_mac(*key, {3, 0, 123456790, 0x5ABCDEF}), mac);
  EXPECT_NE(frame_mac(*key, {3, 0, 123456789 + 512, 0x5ABCDEF}), mac) << "the full counter, not its low bits";
  EXPECT_NE(frame_mac(*key, {3, 0, 123456789, 0x5ABCDEE}), mac);
  const std::uint32_t tag = answer_tag(*key, in, mac);
  EXPECT_NE(tag, mac);
  EXPECT_NE(answer_tag(*other, in, mac), tag);
  EXPECT_NE(answer_tag(*key, in, mac ^ 1), tag);
}
