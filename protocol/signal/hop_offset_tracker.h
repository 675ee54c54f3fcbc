// Signal layer: the frequency offset the fast listener reads its next frames at first (one job
// of hop_listener.h). Clocks and Doppler shift every tone by the same factor (1 + offset); a
// decoded frame says which bin each tone was sent on, and its readings where each was heard.
// Pure: fed decoded frames, no clock.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "profile/link_profile.h"
#include "signal/hop_candidate.h"

namespace dtmf::signal {

class HopOffsetTracker {
 public:
  explicit HopOffsetTracker(const HopPlan& plan) : plan_(plan) {}

  // A frame was decoded from `candidate` with these code symbols (tone_count() of them): the
  // median offset of its tones the decoder did not have to correct, when they agree.
  void confirm(const HopCandidate& candidate, std::span<const std::uint8_t> symbols);
  std::optional<int> offset_ppm() const { return tracked_ppm_; }

 private:
  const HopPlan& plan_;
  std::optional<int> tracked_ppm_;
};

}  // namespace dtmf::signal
