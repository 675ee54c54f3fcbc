// Test support: seed frames as audio, through the link's one renderer (Link::render), for
// tests that send frames no sender plans (a word or tones corrupted on purpose).
#pragma once

#include <vector>

#include "link/seed_link.h"
#include "profile/link_profile.h"

namespace dtmf::test_support {

// The frames one after another, each chord_ms of chord then gap_ms of silence.
inline std::vector<float> seed_audio(const LinkProfile& profile, const std::vector<link::SeedPlannedFrame>& planned) {
  const link::SeedLink seed(profile, {});
  std::vector<link::TransmitFrame> frames;
  for (const auto& p : planned) frames.push_back(seed.transmit_frame(p));
  return seed.render(frames);
}

}  // namespace dtmf::test_support
