#include "signal/bin_reply_listener.h"

#include <algorithm>

namespace dtmf::signal {

std::array<int, 2> reply_tone_indexes(const NamedReply& reply) {
  if (reply.ack) return {reply.sequence, ack_second_tone(reply.sequence)};
  return {0, kNackSecondTone};
}

int ack_second_tone(int sequence) { return (5 * sequence + 3) % 16; }

BinReplyListener::BinReplyListener(const LinkProfile& profile)
    : sample_rate_hz_(profile.sample_rate_hz),
      window_samples_(profile.bins.reply_window_samples),
      hop_(profile.bins.reply_hop_samples),
      bands_(profile.bins.reply_window_samples, profile.bins.reply_band_first_bin, profile.bins.reply_tones_per_band,
             profile.bins.reply_presence_db, profile.bins.reply_dominance_db),
      window_(static_cast<std::size_t>(profile.bins.reply_window_samples),
              static_cast<std::size_t>(profile.bins.reply_hop_samples)) {
  heard_.reserve(16);
}

void BinReplyListener::reset() {
  window_.clear();
  previous_.reset();
  passed_.reset();
}

std::span<const HeardReply> BinReplyListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

void BinReplyListener::analyze_window() {
  const auto r = bands_.analyze(window_.window());
  std::optional<NamedReply> now;
  if (r[0].present && r[1].present) {
    if (r[1].symbol == ack_second_tone(r[0].symbol)) now = NamedReply{true, r[0].symbol};
    else if (r[0].symbol == 0 && r[1].symbol == kNackSecondTone) now = NamedReply{false, 0};
  }
  if (passed_ && now != passed_) passed_.reset();  // re-armed by a window without it
  if (now && now == previous_ && !passed_) {
    passed_ = now;
    const double heard_ms = 1000.0 * static_cast<double>(window_.samples_fed()) / sample_rate_hz_;
    const double start_ms = heard_ms - 1000.0 * (window_samples_ + hop_) / sample_rate_hz_;
    heard_.push_back(HeardReply{*now, start_ms, heard_ms});
  }
  previous_ = now;
}

}  // namespace dtmf::signal
