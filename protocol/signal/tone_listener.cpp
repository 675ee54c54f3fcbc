#include "signal/tone_listener.h"

#include <algorithm>

namespace dtmf::signal {

namespace {
DebounceParams for_symbols_of(DebounceParams params, double symbol_ms) {
  params.symbol_ms = symbol_ms;
  return params;
}
}  // namespace

ToneListener::ToneListener(const LinkProfile& profile, const DetectorParams& detector, double symbol_ms, Decode decode)
    : sample_rate_hz_(profile.sample_rate_hz),
      fft_size_(profile.words().analysis.fft_size),
      analyzer_(profile.words().analysis.fft_size, profile.sample_rate_hz),
      background_(static_cast<std::size_t>(profile.words().analysis.fft_size / 2 + 1),
                  detector.background_rise_db_per_s,
                  static_cast<double>(profile.sample_rate_hz) / profile.hop_samples(),
                  static_cast<float>(amplitude_from_dbfs(detector.noise_gate_dbfs))),
      peaks_(detector, analyzer_.bin_hz(), static_cast<std::size_t>(profile.words().analysis.fft_size / 2 + 1)),
      // Only the bins the peak detector reads: the rest of the spectrum is never looked at.
      phasors_(static_cast<std::size_t>(profile.words().analysis.fft_size / 2 + 1), peaks_.first_read_bin(),
               peaks_.end_read_bin(), detector.background_rise_db_per_s,
               static_cast<double>(profile.sample_rate_hz) / profile.hop_samples(),
               static_cast<float>(amplitude_from_dbfs(detector.noise_gate_dbfs))),
      decode_(std::move(decode)),
      debouncer_(for_symbols_of(profile.words().debounce, symbol_ms)),
      window_(static_cast<std::size_t>(profile.words().analysis.fft_size),
              static_cast<std::size_t>(profile.hop_samples())) {
  // Room for the passes of any usual block; a huge block may grow it once.
  heard_.reserve(64);
}

void ToneListener::reset() {
  window_.clear();
  debouncer_.reset();
  phasors_.reset();
  background_.reset();
  last_peaks_ = {};
}

std::span<const Heard> ToneListener::feed(std::span<const float> samples) {
  heard_.clear();
  window_.feed(samples, [this] { analyze_window(); });
  return heard_;
}

void ToneListener::analyze_window() {
  last_peaks_ = peaks_.detect(background_.remove(phasors_.remove(analyzer_.analyze_phasors(window_.window()))));
  const double end_ms = static_cast<double>(window_.samples_fed()) * 1000.0 / sample_rate_hz_;
  if (const auto pass = debouncer_.on_window(end_ms, decode_(last_peaks_))) {
    const double half_window_ms = 500.0 * fft_size_ / sample_rate_hz_;
    heard_.push_back(Heard{pass->symbol, std::max(0.0, pass->first_detection_ms - half_window_ms), pass->pass_ms});
  }
}

ToneListener chord_listener(const LinkProfile& profile) {
  return ToneListener(profile, profile.words().robot_detector, profile.timing.chord_ms,
                      [plan = profile.words().tones, rules = profile.words().robot_detector](
                          std::span<const Peak> peaks) -> std::optional<Debouncer::Detection> {
                        const auto chord = decode_chord(plan, peaks, rules);
                        if (!chord) return std::nullopt;
                        return Debouncer::Detection{chord->frame, chord->level};
                      });
}

ToneListener reply_listener(const LinkProfile& profile) {
  return ToneListener(profile, profile.words().sender_detector, profile.timing.ack_ms,
                      [plan = profile.words().tones, tolerance = profile.words().sender_detector.tone_tolerance_hz,
                       dominance = profile.words().sender_detector.dominance_db](
                          std::span<const Peak> peaks) -> std::optional<Debouncer::Detection> {
                        const auto reply = decode_reply(plan, peaks, tolerance, dominance);
                        if (!reply) return std::nullopt;
                        return Debouncer::Detection{static_cast<std::uint32_t>(reply->reply), reply->level};
                      });
}

}  // namespace dtmf::signal
