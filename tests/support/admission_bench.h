// A robot's admission on a bench (link/frame_admission.h): frames made bit by bit, with the
// keys and counters a test chooses, and given to a FrameAdmission as heard — no audio, so a
// test reaches each rule (link/admission_rules.h) and each reading (link/frame_reading.h)
// directly. Robot 2 (kMe) hears; robot 5 (kOther) is another robot of the room.
#pragma once

#include <chrono>
#include <memory>
#include <optional>

#include "command/command.h"
#include "command/command_payload.h"
#include "link/frame_admission.h"
#include "profile/link_profile.h"
#include "reliability/command_frame.h"
#include "reliability/plain_renewal.h"
#include "reliability/renewal_frame.h"
#include "reliability/sealed_frame.h"
#include "security/counter_clock.h"
#include "security/counter_store.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "support/test_key.h"

namespace admission_bench {

using namespace dtmf;

inline constexpr std::uint8_t kMe = 2;
inline constexpr std::uint8_t kOther = 5;
inline constexpr int kPlainChords = 2;
inline constexpr int kSealedChords = 3;
// How long after its start a bench frame is heard (about an 80-bit frame's air time).
inline constexpr double kHeardAfterMs = 150;

inline std::shared_ptr<const security::LinkKey> own_key() { return test_support::test_key(kMe); }
inline std::shared_ptr<const security::LinkKey> other_key() { return test_support::test_key(7); }
inline std::shared_ptr<const security::LinkKey> room_key() { return test_support::test_key(99); }

inline std::uint32_t payload(const command::Command& command) { return command::encode_payload(command); }
// A STOP with a field: a payload no sender makes.
inline const std::uint32_t kUndecodable = payload(command::Stop{}) | 1u;
// A counter a day past this robot's clock, far beyond the margin.
inline std::uint64_t ahead_counter() {
  return security::clock_counter_floor(std::chrono::system_clock::now()) + security::kClockMargin +
         std::uint64_t{86400} * security::kCountersPerSecond;
}

inline reliability::FrameBits plain(std::uint8_t address, std::uint8_t sequence, std::uint32_t payload_bits) {
  return reliability::command_frame_pack({address, sequence, payload_bits});
}
// `mac_payload`: what the MAC covers; a frame in synchronisation form carries its whole
// counter and no payload.
inline reliability::FrameBits sealed(const security::LinkKey& key, std::uint8_t address, reliability::SealedForm form,
                                     std::uint64_t counter, std::uint32_t mac_payload) {
  const bool sync = form == reliability::SealedForm::Sync;
  const reliability::SealedFrame f{
      address, form, sync ? counter : security::counter_low_bits(counter), sync ? 0u : mac_payload,
      security::frame_mac(key, {address, static_cast<std::uint8_t>(form), counter, mac_payload})};
  return reliability::sealed_frame_pack(f);
}
inline reliability::FrameBits sealed_command(const security::LinkKey& key, std::uint64_t counter,
                                             const command::Command& c) {
  return sealed(key, kMe, reliability::SealedForm::Command, counter, payload(c));
}
inline reliability::FrameBits sync(const security::LinkKey& key, std::uint64_t counter) {
  return sealed(key, kMe, reliability::SealedForm::Sync, counter, 0);
}
inline reliability::FrameBits sync_stop(const security::LinkKey& key, std::uint64_t counter) {
  return sealed(key, kMe, reliability::SealedForm::Sync, counter, payload(command::Stop{}));
}
// A stop for every robot under the room key, addressed to another robot: taken all the same.
inline reliability::FrameBits room_stop(std::uint64_t room_counter) {
  return sealed(*room_key(), kOther, reliability::SealedForm::Sync, room_counter, payload(command::Stop{true}));
}
// A joint renewal whose slots all name this robot, of the sealed velocity of counter `renewed`.
inline reliability::FrameBits joint_renewal(std::uint64_t counter, std::uint64_t renewed) {
  const std::uint32_t mac = security::frame_mac(*own_key(), security::renewal_mac_input(kMe, counter, renewed)) >>
                            (32 - reliability::kRenewalMacBits);
  reliability::RenewalFrame f;
  f.slots.fill({kMe, mac});
  f.counter_low = security::counter_low_bits(counter);
  return reliability::renewal_frame_pack(f);
}
// A plain joint renewal numbered `number`, of the velocity frame numbered `sequence` of `address`.
inline reliability::FrameBits plain_renewal(std::uint32_t number, std::uint8_t address, std::uint8_t sequence) {
  reliability::PlainRenewal renewal;
  renewal.number = number;
  renewal.slots.fill({address, sequence});
  return reliability::command_frame_pack(reliability::plain_renewal_pack(renewal));
}

enum class Keys { None, Own, OwnAndRoom };

struct Bench {
  // `last_accepted`, `room_last`: the counters this robot kept before.
  explicit Bench(Keys keys, std::uint64_t last_accepted = 0, std::uint64_t room_last = 0)
      : counters(std::make_shared<security::MemoryCounterStore>(1, last_accepted)),
        room_counters(std::make_shared<security::MemoryCounterStore>(1, room_last)),
        robot(profile_by_name("fast"), options(keys)) {}

  link::LinkOptions options(Keys keys) const {
    link::LinkOptions o;
    o.address = kMe;
    if (keys != Keys::None) {
      o.key = own_key();
      o.counters = counters;
    }
    if (keys == Keys::OwnAndRoom) {
      o.room_key = room_key();
      o.room_counters = room_counters;
    }
    return o;
  }
  std::optional<link::Reception> hear(reliability::FrameBits bits, int chords, double start_ms, bool intact = true) {
    link::HeardHopFrame h;
    h.start_ms = start_ms;
    h.heard_ms = start_ms + kHeardAfterMs;
    h.chords = chords;
    h.intact = intact;
    h.bits = bits;
    return robot.admit(h);
  }

  std::shared_ptr<security::MemoryCounterStore> counters;
  std::shared_ptr<security::MemoryCounterStore> room_counters;
  link::FrameAdmission robot;
};

}  // namespace admission_bench
