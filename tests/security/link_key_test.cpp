// The security layer's key file: made with mode 0600, read back, refused when others may read
// it or when it is damaged, and never quoted in an error.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "security/frame_mac.h"
#include "security/link_key.h"
#include "support/temp_dir.h"

using namespace dtmf::security;
namespace fs = std::filesystem;

namespace {

// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-key") {}
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

namespace {

// Every 8-character window of `secret` that occurs in `text` (none, if nothing of it leaked).
std::vector<std::string> leaked_windows(const std::string& text, const std::string& secret) {
  std::vector<std::string> found;
  for (std::size_t at = 0; at + 8 <= secret.size(); ++at) {
    if (text.find(secret.substr(at, 8)) != std::string::npos) found.push_back(secret.substr(at, 8));
  }
  return found;
}

// A key whose hex spelling starts with digits no English word or path here holds, so that a
// short window of it in an error means a leak, not chance.
std::shared_ptr<const LinkKey> recognisable_key() {
  std::array<unsigned char, kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(0x93 + 37 * i);
  bytes[0] = 0x9d;
  bytes[1] = 0x7c;
  return LinkKey::from_bytes(bytes);
}

}  // namespace

// Issue 34: "key=<hex>", "key:<hex>" or a bare key used to be quoted as an unknown field,
// 20 characters of it (80 bits of the key) in the error and so in the service's log.
TEST(LinkKey, AMalformedLineIsRefusedByItsNumberWithoutAByteOfTheKey) {
  TempDir dir;
  const fs::path file = dir.path / "k";
  const auto key = recognisable_key();
  key->save(file);
  const std::string text = read_all(file);
  const std::string hex = key_line(text);
  ASSERT_EQ(hex.substr(0, 4), "9d7c");
  const std::string header = text.substr(0, text.find("\nkey ") + 1);  // the comment and the key-id line
  std::string non_hex = hex;
  non_hex[20] = 'g';
  std::string upper = "KEY " + hex;
  const std::vector<std::string> bad_lines = {
      "key=" + hex,
      "key:" + hex,
      hex,
      "key  " + hex + " extra",
      "key " + hex + " " + hex,
      "key " + non_hex,
      "key " + hex.substr(0, 63),
      "key " + hex + "0",
      "key " + hex.substr(0, 32) + " " + hex.substr(32),
      "key 0x" + hex.substr(0, 62),
      upper,
      "key-id " + hex,
      "keys " + hex,
      "key" + hex,
      "  key=" + hex + "  ",
      "\"key\": \"" + hex + "\"",
  };
  for (const std::string& bad : bad_lines) {
    fs::remove(file);
    std::ofstream(file) << header << bad << "\n";
    ::chmod(file.c_str(), 0600);
    try {
      LinkKey::load(file);
      ADD_FAILURE() << "accepted line 3: " << bad;
    } catch (const KeyFileError& e) {
      std::string what = e.what();
      EXPECT_TRUE(leaked_windows(what, hex).empty()) << what << "\nfrom: " << bad;
      EXPECT_NE(what.find(" line 3:"), std::string::npos) << what;
      EXPECT_NE(what.find("'key <64 hex digits>'"), std::string::npos) << what;
      EXPECT_NE(what.find("dtmfctl keygen"), std::string::npos) << what;
      // Not even the first two bytes, nor any part of the line (the file's name aside).
      for (std::size_t at; (at = what.find(file.string())) != std::string::npos;) what.erase(at, file.string().size());
      EXPECT_EQ(what.find("9d7c"), std::string::npos) << what;
      EXPECT_EQ(what.find("extra"), std::string::npos) << what;
      EXPECT_EQ(what.find("KEY"), std::string::npos) << what;
      EXPECT_EQ(what.find("keys"), std::string::npos) << what;
    }
  }
}

TEST(LinkKey, AMalformedKeyIdLineIsRefusedByItsNumber) {
  TempDir dir;
  const fs::path file = dir.path / "k";
  const auto key = recognisable_key();
  key->save(file);
  const std::string hex = key_line(read_all(file));
  for (const std::string& id : {std::string("0x") + key->id_hex().substr(0, 6), "+" + key->id_hex().substr(1),
                                key->id_hex() + "0", key->id_hex().substr(1), key->id_hex() + " x"}) {
    fs::remove(file);
    std::ofstream(file) << "key " << hex << "\n\nkey-id " << id << "\n";
    ::chmod(file.c_str(), 0600);
    try {
      LinkKey::load(file);
      ADD_FAILURE() << "accepted key-id " << id;
    } catch (const KeyFileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(" line 3:"), std::string::npos) << what;
      EXPECT_NE(what.find("'key-id <8 hex digits>'"), std::string::npos) << what;
      EXPECT_TRUE(leaked_windows(what, hex).empty()) << what;
    }
  }
  // What keygen writes still loads, and so do blank lines, comments and CRLF line ends.
  fs::remove(file);
  std::ofstream(file) << "# a comment\r\n\r\n  key-id " << key->id_hex() << "\r\nkey\t" << hex << "  \r\n";
  ::chmod(file.c_str(), 0600);
  EXPECT_EQ(LinkKey::load(file)->id(), key->id());
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
  const AnswerTag tag = answer_tag(*key, in, mac);
  // The direction byte keeps a tag from being a frame's MAC: its first 32 bits differ.
  EXPECT_NE((std::uint32_t{tag[0]} << 24) | (std::uint32_t{tag[1]} << 16) | (std::uint32_t{tag[2]} << 8) | tag[3], mac);
  EXPECT_NE(answer_tag(*other, in, mac), tag);
  EXPECT_NE(answer_tag(*key, in, mac ^ 1), tag);
}
