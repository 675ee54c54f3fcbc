// A frame read once (link/frame_reading.h): each kind from its bits, every MAC-decided reading
// verified before one is chosen, and the rule that chooses where two hold.
#include <gtest/gtest.h>

#include <array>

#include "link/frame_reading.h"
#include "support/admission_bench.h"

using namespace dtmf;
using namespace admission_bench;
using link::reading::FrameKind;
using link::reading::SealedKind;

namespace {

link::reading::ReadingContext context(std::optional<std::uint64_t> renewable = std::nullopt) {
  static const auto own = own_key();
  static const auto room = room_key();
  link::reading::ReadingContext c;
  c.address = kMe;
  c.key = own.get();
  c.room_key = room.get();
  c.last_accepted = 100;
  c.renewable_counter = renewable;
  return c;
}

FrameKind read(reliability::FrameBits bits, int chords, const link::reading::ReadingContext& c = context()) {
  link::HeardHopFrame h;
  h.chords = chords;
  h.intact = true;
  h.bits = bits;
  return link::reading::kind_of(link::reading::read_frame(h, chords == kSealedChords, c));
}

// Every combination of what verified (room stop, own command, renewal, addressed here), and
// the reading it gets.
struct Collision {
  bool room, command, renewal, here;
  SealedKind kind;
};
// clang-format off
constexpr std::array<Collision, 16> kCollisions{{
  // A stop for every robot wins over anything under this robot's key.
  {true,  true,  true,  true,  SealedKind::RoomStop},    {true,  true,  true,  false, SealedKind::RoomStop},
  {true,  true,  false, true,  SealedKind::RoomStop},    {true,  true,  false, false, SealedKind::RoomStop},
  {true,  false, true,  true,  SealedKind::RoomStop},    {true,  false, true,  false, SealedKind::RoomStop},
  {true,  false, false, true,  SealedKind::RoomStop},    {true,  false, false, false, SealedKind::RoomStop},
  // A command for this address wins over a renewal; one for another address is none of ours.
  {false, true,  true,  true,  SealedKind::OwnCommand},  {false, true,  true,  false, SealedKind::JointRenewal},
  {false, true,  false, true,  SealedKind::OwnCommand},  {false, true,  false, false, SealedKind::Elsewhere},
  {false, false, true,  true,  SealedKind::JointRenewal}, {false, false, true,  false, SealedKind::JointRenewal},
  {false, false, false, true,  SealedKind::Unverified},  {false, false, false, false, SealedKind::Elsewhere},
}};
// clang-format on

}  // namespace

TEST(FrameReading, WhereReadingsCollideTheRuleDecidesNotTheOrderOfTrials) {
  for (const Collision& c : kCollisions) {
    EXPECT_EQ(link::reading::sealed_kind(c.room, c.command, c.renewal, c.here), c.kind)
        << c.room << c.command << c.renewal << c.here;
  }
}

TEST(FrameReading, PlainFramesAreToldByTheirPayloadThenTheirAddress) {
  EXPECT_EQ(read(plain(kMe, 1, payload(command::Stop{})), kPlainChords), FrameKind::PlainCommand);
  EXPECT_EQ(read(plain(kMe, 1, kUndecodable), kPlainChords), FrameKind::PlainCommand);
  EXPECT_EQ(read(plain(kOther, 1, payload(command::Stop{})), kPlainChords), FrameKind::Elsewhere);
  EXPECT_EQ(read(plain(kOther, 1, payload(command::Stop{true})), kPlainChords), FrameKind::PlainRoomStop);
  EXPECT_EQ(read(plain_renewal(9, kMe, 3), kPlainChords), FrameKind::PlainRenewal);
  EXPECT_EQ(read(plain_renewal(9, kOther, 3), kPlainChords), FrameKind::Elsewhere);
}

TEST(FrameReading, SealedFramesAreWhatTheirMacSays) {
  EXPECT_EQ(read(room_stop(5), kSealedChords), FrameKind::RoomStop);
  EXPECT_EQ(read(sync(*own_key(), 500), kSealedChords), FrameKind::Synchronisation);
  EXPECT_EQ(read(sync_stop(*own_key(), 500), kSealedChords), FrameKind::SealedCommand);
  EXPECT_EQ(read(sealed_command(*own_key(), 101, command::Stop{}), kSealedChords), FrameKind::SealedCommand);
  EXPECT_EQ(read(sealed_command(*other_key(), 101, command::Stop{}), kSealedChords), FrameKind::Unverified);
  EXPECT_EQ(
      read(sealed(*own_key(), kOther, reliability::SealedForm::Command, 101, payload(command::Stop{})), kSealedChords),
      FrameKind::Elsewhere);
  // A renewal only while the velocity it is bound to is the one taken last.
  EXPECT_EQ(read(joint_renewal(101, 100), kSealedChords, context(100)), FrameKind::JointRenewal);
  EXPECT_EQ(read(joint_renewal(101, 100), kSealedChords, context(99)), FrameKind::Unverified);
  EXPECT_EQ(read(joint_renewal(101, 100), kSealedChords, context()), FrameKind::Unverified);
  // Without keys nothing sealed verifies: this robot's address is its to refuse, unchecked.
  link::reading::ReadingContext keyless = context();
  keyless.key = nullptr;
  keyless.room_key = nullptr;
  EXPECT_EQ(read(room_stop(5), kSealedChords, keyless), FrameKind::Elsewhere);
  EXPECT_EQ(read(sealed_command(*own_key(), 101, command::Stop{}), kSealedChords, keyless), FrameKind::Unverified);
}

TEST(FrameReading, BrokenFramesAndEchoesAreReadBeforeTheirBits) {
  link::HeardHopFrame h;
  h.chords = kSealedChords;
  h.bits = sealed_command(*own_key(), 101, command::Stop{});
  EXPECT_EQ(link::reading::kind_of(link::reading::read_frame(h, true, context())), FrameKind::Broken);
  reliability::EchoMemory echoes(5000);
  echoes.remember(h.bits, 0);
  echoes.remember(sync(*own_key(), 500), 100);
  link::reading::ReadingContext c = context();
  c.echoes = &echoes;
  h.intact = true;
  h.heard_ms = 200;
  EXPECT_EQ(link::reading::kind_of(link::reading::read_frame(h, true, c)), FrameKind::Echo);
}

// A command whose bits also pass this robot's renewal slot (one frame in about 2^18, found by
// search, as JointRenewal.ACommandThatAlsoReadsAsARenewalIsTheCommand finds it): both readings
// verify, and the frame is read as the command.
TEST(FrameReading, ACommandThatAlsoVerifiesAsARenewalIsReadAsTheCommand) {
  const std::uint64_t velocity_counter = 1;  // the velocity taken last, and the last accepted
  const auto key = own_key();
  link::reading::ReadingContext c = context(velocity_counter);
  c.last_accepted = velocity_counter;
  std::optional<reliability::FrameBits> both;
  for (int linear = -2047; linear <= 2047 && !both; ++linear) {
    for (int angular = -127; angular <= 127 && !both; ++angular) {
      const auto bits =
          sealed_command(*key, velocity_counter + 1, command::Velocity{linear / 2047.0, angular / 127.0, 1.0});
      const auto v = link::reading::verify_sealed(*reliability::sealed_frame_unpack(bits), bits, c);
      if (v.command_payload && v.renewal_counter && *v.renewal_counter != velocity_counter) both = bits;
    }
  }
  ASSERT_TRUE(both) << "no velocity frame verifies as a renewal too: search wider";
  EXPECT_EQ(read(*both, kSealedChords, c), FrameKind::SealedCommand);
}
