// The joint renewal's 80 bits (reliability/renewal_frame.h): three slots and a counter under
// the sealed frame's CRC-8.
#include "reliability/renewal_frame.h"

#include <gtest/gtest.h>

#include "reliability/sealed_frame.h"

using namespace dtmf::reliability;

TEST(RenewalFrame, PacksAndUnpacksEveryField) {
  const RenewalFrame f{{RenewalSlot{1, 0x3FFFF}, RenewalSlot{6, 0x12345}, RenewalSlot{7, 0}}, 0x1A5};
  const FrameBits bits = renewal_frame_pack(f);
  EXPECT_EQ(bits.value() >> kSealedFrameBits, 0u) << "80 bits";
  EXPECT_EQ(static_cast<unsigned>(bits.value() >> 77), 1u) << "slot 0's address leads, where a sealed frame's is";
  EXPECT_EQ(renewal_frame_unpack(bits), f);
}

TEST(RenewalFrame, AnyFlippedBitFailsTheCheck) {
  const FrameBits bits =
      renewal_frame_pack({{RenewalSlot{2, 0x2AAAA}, RenewalSlot{3, 0x15555}, RenewalSlot{2, 0x2AAAA}}, 77});
  for (int bit = 0; bit < kSealedFrameBits; ++bit) {
    EXPECT_FALSE(renewal_frame_unpack(FrameBits::wide(bits.value() ^ (WideBits{1} << bit)))) << "bit " << bit;
  }
}

TEST(RenewalFrame, EveryIntactSealedFrameAlsoReadsAsARenewal) {
  // Nothing marks a renewal: only a slot's MAC tells (link/frame_admission.h).
  const FrameBits sealed = sealed_frame_pack({3, SealedForm::Command, 12, 0x4ABCDE, 0xDEADBEEF});
  const auto read = renewal_frame_unpack(sealed);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->slots[0].address, 3);
  EXPECT_EQ(renewal_frame_pack(*read), sealed);
}
