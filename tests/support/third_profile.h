// Test helper: a third profile, made in the tests and registered as a deployment would
// register its own (profile/profile_registry.h): the fast profile's hopped plan with every
// command band 8 bins (200 Hz) higher, and a 600 ms ACK timeout. Nothing in server/, robot_agent/ or
// clients/ knows it: they take it by name. The conformance suite and a whole-system test
// run it.
#pragma once

#include <functional>

#include "profile/profile_registry.h"

namespace dtmf::test_support {

inline constexpr const char* kThirdProfile = "fast-high";

inline const LinkProfile& third_profile() {
  static const LinkProfile& profile = [] {
    LinkProfile p = fast_profile();
    p.name = kThirdProfile;
    p.description = "a test's profile: fast's plan 200 Hz higher";
    HopPlan& h = p.hops();
    for (auto& chord : h.band_first_bin) {
      for (int& first_bin : chord) first_bin += 8;
    }
    p.timing.ack_timeout_ms = 600;
    return std::cref(register_profile(std::move(p)));
  }();
  return profile;
}

}  // namespace dtmf::test_support
