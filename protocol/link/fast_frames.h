// The fast profile's frames as its sender plays them: bits, tones, audio and pacing, for a
// plain 50-bit command frame, a sealed 80-bit one (its answer's tag included) and a keyed
// joint renewal. Shared by the link (fast_link.cpp), which numbers commands, and the renewal
// planner (renewal_planner.h), which numbers renewals: one place makes each kind's sound, so
// a renewal sounds exactly as the link's own frames do. Pure: no I/O, no clock.
#pragma once

#include <cstdint>

#include "link/transmit_plan.h"
#include "profile/link_profile.h"
#include "reliability/command_frame.h"
#include "reliability/renewal_frame.h"
#include "security/frame_mac.h"
#include "security/link_key.h"

namespace dtmf::link {

// The tag the ACK to an authenticated frame spells, as its chord's symbols, in the bins the
// frame left free.
reliability::TagChordSymbols reply_tag(const security::LinkKey& key, const security::FrameMacInput& input,
                                       std::uint32_t mac, const reliability::BandValueSet& taken);

// `frame` (50 bits) as it sounds, paced for its answer in the reply bands.
TransmitFrame command_transmit_frame(const LinkProfile& profile, const reliability::CommandFrame& frame);

// What a sealed frame carries besides its key: synchronisation frames carry the whole
// counter, command frames its low bits.
struct SealedContent {
  std::uint8_t address = 0;
  std::uint32_t payload = 0;
  bool synchronisation = false;
  std::uint64_t counter = 0;
};
// A sealed frame (80 bits) under `key`, paced for its tag chord, which sounds in the frame bands.
TransmitFrame sealed_transmit_frame(const LinkProfile& profile, const security::LinkKey& key,
                                    const SealedContent& content);

// A keyed joint renewal (80 bits) numbered `counter`: no robot answers it.
TransmitFrame renewal_transmit_frame(const LinkProfile& profile, const reliability::RenewalFrame& renewal,
                                     std::uint64_t counter);

}  // namespace dtmf::link
