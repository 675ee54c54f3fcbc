#include "signal/hop_band_gate.h"

#include <algorithm>

#include "signal/hop_candidate.h"
#include "units/decibels.h"

namespace dtmf::signal {

HopBandGate::HopBandGate(const HopPlan& plan, int lo_bin)
    : plan_(plan), lo_bin_(lo_bin), gate_ratio_(static_cast<float>(units::power_ratio_from_db(plan.gate_db))) {}

void HopBandGate::score(HopWindow& window) const {
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) {
      // The band's best excess over the mean of the other bins' raw power (the excess is zero
      // wherever a bin just fell to a new low, so its mean is no floor to measure noise against).
      const std::size_t from = static_cast<std::size_t>(
          plan_.band_first_bin[static_cast<std::size_t>(c)][static_cast<std::size_t>(b)] - lo_bin_ - 2);
      const int n = plan_.tones_per_band + 4;
      float best = 0, sum = 0;
      std::size_t at = from;
      for (std::size_t i = from; i < from + static_cast<std::size_t>(n); ++i) {
        if (window.excess[i] > best) {
          best = window.excess[i];
          at = i;
        }
        sum += window.power[i];
      }
      const float others = (sum - window.power[at]) / static_cast<float>(n - 1);
      window.band_score[static_cast<std::size_t>(hop_tone_index(c, b))] = best / std::max(others, 1e-30f);
    }
  }
}

HopBandGate::Verdict HopBandGate::judge(std::span<const HopWindow* const> chord_windows) const {
  const int chords = static_cast<int>(chord_windows.size());
  int weakest = HopPlan::kBandsPerChord, total = 0;
  for (int c = 0; c < chords; ++c) {
    const HopWindow& w = *chord_windows[static_cast<std::size_t>(c)];
    int loud = 0;
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b)
      loud += w.band_score[static_cast<std::size_t>(hop_tone_index(hop_band_set(c), b))] >= gate_ratio_ ? 1 : 0;
    weakest = std::min(weakest, loud);
    total += loud;
  }
  if (weakest >= plan_.gate_bands) return Verdict::Open;
  const bool reread = plan_.reread_delay_hops > 0 && weakest >= plan_.reread_gate_bands &&
                      total >= chords * HopPlan::kBandsPerChord / 2;
  return reread ? Verdict::RereadOnly : Verdict::Closed;
}

}  // namespace dtmf::signal
