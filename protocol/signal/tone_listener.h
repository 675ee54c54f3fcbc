// Signal layer: the listening side put together — audio in, debounced symbols out.
//
//   samples -> sliding window (fft_size, hop = rate / analyses_per_s) -> spectrum
//           -> less each bin's steady phasor (a whine, phase and all) and then its steady
//              background power (the floor) -> band-pass, gate, N loudest peaks
//           -> chord or reply -> debouncer
//
// chord_listener() makes the robot's (command chords, robot detector), reply_listener()
// the sender's (ACK / NACK, sender detector). Times are milliseconds since the first sample
// fed. The stream is taken to be preceded by silence, so a chord at time 0 is heard.
// Once constructed, feeding allocates nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/chord_decoder.h"
#include "signal/debouncer.h"
#include "signal/peak_detector.h"
#include "signal/sliding_window.h"
#include "signal/spectrum.h"
#include "signal/steady_background.h"
#include "signal/steady_phasors.h"
#include "signal/tone_plan.h"

namespace dtmf::signal {

// One debounced symbol: when it started sounding (centre of the first window that heard
// it) and when it passed the debouncer (end of the window that completed it).
struct Heard {
  std::uint32_t symbol;
  double start_ms;
  double heard_ms;
};

class ToneListener {
 public:
  using Decode = std::function<std::optional<Debouncer::Detection>(std::span<const Peak>)>;

  // symbol_ms: how long one symbol sounds at the sender (the debouncer's dropout rule).
  ToneListener(const LinkProfile& profile, const DetectorParams& detector, double symbol_ms, Decode decode);

  // Symbols that passed within `samples`; the span is valid until the next call.
  std::span<const Heard> feed(std::span<const float> samples);

  // Peaks of the latest analysis window, loudest first (for diagnostics).
  std::span<const Peak> last_peaks() const { return last_peaks_; }
  void reset();

 private:
  void analyze_window();

  int sample_rate_hz_;
  int fft_size_;
  SpectrumAnalyzer analyzer_;
  SteadyBackground background_;
  PeakDetector peaks_;
  SteadyPhasors phasors_;
  Decode decode_;
  Debouncer debouncer_;
  SlidingWindow window_;  // the latest fft_size samples, analysed every hop
  std::span<const Peak> last_peaks_;
  std::vector<Heard> heard_;
};

// The robot's listener: symbols are 16-bit frames (not yet CRC-checked).
ToneListener chord_listener(const LinkProfile& profile);

// The sender's listener: symbols are Reply values (static_cast<Reply>(symbol)).
ToneListener reply_listener(const LinkProfile& profile);

}  // namespace dtmf::signal
