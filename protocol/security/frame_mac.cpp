#include "security/frame_mac.h"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace dtmf::security {

namespace {

constexpr char kLabel[] = "dtmf-teleop/1";
constexpr std::size_t kLabelBytes = sizeof kLabel - 1;
constexpr std::size_t kMessageBytes = kLabelBytes + 1 + 4 + 1 + 1 + 8 + 4;

void put_be(unsigned char* at, std::uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) {
    at[i] = static_cast<unsigned char>(value & 0xFF);
    value >>= 8;
  }
}

using Digest = std::array<unsigned char, crypto_generichash_BYTES_MIN>;  // 128 bits

Digest digest(const LinkKey& key, Direction direction, const FrameMacInput& in, std::uint32_t body) {
  std::array<unsigned char, kMessageBytes> message{};
  unsigned char* at = message.data();
  std::memcpy(at, kLabel, kLabelBytes);
  at += kLabelBytes;
  *at++ = static_cast<unsigned char>(direction);
  put_be(at, key.id(), 4);
  at += 4;
  *at++ = in.address;
  *at++ = in.form;
  put_be(at, in.counter, 8);
  at += 8;
  put_be(at, body, 4);
  Digest out{};
  crypto_generichash(out.data(), out.size(), message.data(), message.size(), key.bytes().data(), key.bytes().size());
  return out;
}

}  // namespace

std::uint32_t frame_mac(const LinkKey& key, const FrameMacInput& input) {
  const Digest d = digest(key, Direction::ToRobot, input, input.payload);
  return (std::uint32_t{d[0]} << 24) | (std::uint32_t{d[1]} << 16) | (std::uint32_t{d[2]} << 8) | d[3];
}

AnswerTag answer_tag(const LinkKey& key, const FrameMacInput& frame, std::uint32_t mac) {
  const Digest d = digest(key, Direction::ToSender, frame, mac);
  AnswerTag tag{};
  std::copy_n(d.begin(), tag.size(), tag.begin());
  return tag;
}

}  // namespace dtmf::security
