// The unkeyed joint renewal's payload (reliability/plain_renewal.h): three slots of an
// address and a velocity's sequence number, and its number in the frame's first seven bits.
#include "reliability/plain_renewal.h"

#include <gtest/gtest.h>

#include <random>

#include "command/command_payload.h"
#include "command/random_command.h"

using namespace dtmf;
using namespace dtmf::reliability;

TEST(PlainRenewal, PacksAndUnpacksEveryField) {
  const PlainRenewal r{0x5B, {PlainRenewalSlot{1, 15}, PlainRenewalSlot{6, 0}, PlainRenewalSlot{7, 9}}};
  const CommandFrame frame = plain_renewal_pack(r);
  EXPECT_EQ(frame.address, 0x5B >> 4) << "the number's high bits in the address field";
  EXPECT_EQ(frame.sequence, 0xB);
  EXPECT_EQ(frame.payload >> 24, 7u) << "kind 7, EXTENDED";
  EXPECT_EQ(plain_renewal_unpack(frame), r);
  // Through the frame's bits and its CRC, as the robot hears it.
  EXPECT_EQ(plain_renewal_unpack(*command_frame_unpack(command_frame_pack(frame))), r);
}

TEST(PlainRenewal, NoCommandAPayloadCanCarryReadsAsARenewal) {
  // A renewal is never a command, nor a command a renewal: every command's payload decodes, and
  // none of them unpacks as a renewal, while no renewal's payload decodes as a command.
  std::mt19937_64 rng(37);
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t payload = command::encode_payload(command::random_command(rng));
    EXPECT_FALSE(plain_renewal_unpack({static_cast<std::uint8_t>(i & 7), static_cast<std::uint8_t>(i & 15), payload}))
        << command::describe(*command::decode_payload(payload).command);
  }
  const CommandFrame renewal = plain_renewal_pack({3, {PlainRenewalSlot{2, 4}, PlainRenewalSlot{2, 4}, {2, 4}}});
  EXPECT_FALSE(command::decode_payload(renewal.payload).command) << "a renewal read as a command";
}

TEST(PlainRenewal, OtherExtendedSubKindsAreNoRenewal) {
  CommandFrame frame = plain_renewal_pack({1, {}});
  frame.payload ^= 1u << 21;  // sub-kind 1 -> 0
  EXPECT_FALSE(plain_renewal_unpack(frame));
  frame.payload ^= 3u << 21;  // sub-kind 2
  EXPECT_FALSE(plain_renewal_unpack(frame));
}
