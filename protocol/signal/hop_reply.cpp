#include "signal/hop_reply.h"

#include <algorithm>
#include <cmath>

namespace dtmf::signal {

namespace {
constexpr int kMarginBins = 2;
}  // namespace

HopReplyListener::HopReplyListener(const LinkProfile& profile, Read read)
    : hops_(profile.hops),
      read_(std::move(read)),
      sample_rate_hz_(profile.sample_rate_hz),
      presence_ratio_(static_cast<float>(std::pow(10.0, profile.hops.reply_presence_db / 10.0))),
      onset_ratio_(static_cast<float>(std::pow(10.0, profile.hops.reply_onset_db / 10.0))),
      lo_bin_(*std::min_element(profile.hops.reply_band_first_bin.begin(), profile.hops.reply_band_first_bin.end()) -
              kMarginBins),
      windows_back_(profile.hops.reply_samples() / profile.hops.reply_hop_samples + 1),
      bins_(profile.hops.reply_window_samples, lo_bin_,
            *std::max_element(profile.hops.reply_band_first_bin.begin(), profile.hops.reply_band_first_bin.end()) +
                profile.hops.reply_tones_per_band + kMarginBins - lo_bin_),
      window_(static_cast<std::size_t>(profile.hops.reply_window_samples),
              static_cast<std::size_t>(profile.hops.reply_hop_samples)) {
  ring_.assign(static_cast<std::size_t>(windows_back_ + 1),
               std::vector<float>(static_cast<std::size_t>(bins_.bins()), 0.0f));
  heard_.reserve(4);
}

std::span<const HeardReply> HopReplyListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

void HopReplyListener::analyze_window() {
  newest_ = (newest_ + 1) % ring_.size();
  std::vector<float>& now = ring_[newest_];
  bins_.analyze(window_.window(), now);
  ++windows_;
  const std::vector<float>& before = ring_[(newest_ + 1) % ring_.size()];
  std::array<int, 4> tone{-1, -1, -1, -1};  // each band's tone, -1 when it does not count
  for (std::size_t b = 0; b < 4; ++b) {
    const int first = hops_.reply_band_first_bin[b] - lo_bin_;
    const int n = hops_.reply_tones_per_band;
    int best = 0;
    for (int v = 0; v < n; ++v) {
      scratch_[static_cast<std::size_t>(v)] = now[static_cast<std::size_t>(first + v)];
      if (scratch_[static_cast<std::size_t>(v)] > scratch_[static_cast<std::size_t>(best)]) best = v;
    }
    const auto at = static_cast<std::size_t>(first + best);
    const float top = now[at];
    // The band's median, its guard bins included so that a band of one tone has a floor.
    scratch_[static_cast<std::size_t>(n)] = now[static_cast<std::size_t>(first - 1)];
    scratch_[static_cast<std::size_t>(n + 1)] = now[static_cast<std::size_t>(first + n)];
    auto* end = scratch_.data() + n + 2;
    std::nth_element(scratch_.data(), scratch_.data() + (n + 2) / 2, end);
    const float median = scratch_[static_cast<std::size_t>((n + 2) / 2)];
    // (The stream is taken to be preceded by silence: the ring starts as zeros.)
    if (top > presence_ratio_ * median && top > onset_ratio_ * before[at]) tone[b] = best;
  }
  const int reading = read_(tone);
  if (reading < 0) passed_ = -1;  // a window without a reply re-arms
  if (reading >= 0 && reading == last_ && reading != passed_) {
    passed_ = reading;
    const double ms_per_sample = 1000.0 / sample_rate_hz_;
    HeardReply h;
    h.reply = reading;
    h.heard_ms = static_cast<double>(window_.samples_fed()) * ms_per_sample;
    h.start_ms =
        h.heard_ms - (hops_.reply_window_samples + hops_.reply_hop_samples + hops_.reply_edge_samples) * ms_per_sample;
    heard_.push_back(h);
  }
  last_ = reading;
}

}  // namespace dtmf::signal
