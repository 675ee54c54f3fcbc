// Physical layer: the frequency response of a microphone or a loudspeaker.
//
// A response is given as breakpoints (frequency in Hz : gain in dB), joined by straight
// lines on a log-frequency axis and held flat beyond the first and last. It is realised
// as a linear-phase FIR of kResponseTaps taps (frequency sampling on a fine grid, then a
// Blackman window), so it changes levels, never the shape of a chord in time; the price is
// a delay of (kResponseTaps - 1) / 2 samples (5.3 ms at 48 kHz) per response, about what a
// real device's converters add. With 511 taps at 48 kHz the FIR resolves about 200 Hz:
// features below that (a 100 Hz high-pass corner) come out smoothed, which does not matter
// to the link's tones (4.5 to 16 kHz) and keeps the FIR short.
//
// Presets (why each shape, in docs/protocol.md §7):
//   flat          no filter at all
//   cheap-mic     an electret/MEMS capsule in a plastic housing: a 100 Hz high-pass
//                 (-3 dB), flat 200 Hz to 5 kHz, -3 dB by 10 kHz, -12 dB at 16 kHz
//   small-speaker a 40-50 mm full-range driver in a small box: no bass (-3 dB at 400 Hz,
//                 -24 dB at 100 Hz), a +3 dB presence peak near 3 kHz, -6 dB at 12 kHz,
//                 -15 dB at 16 kHz
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace dtmf::sim {

inline constexpr int kResponseTaps = 511;

struct FrequencyResponse {
  std::string name = "flat";                         // a preset's name, or what was parsed
  std::vector<std::pair<double, double>> points_db;  // (Hz, dB); empty: flat, no filter

  bool flat() const { return points_db.empty(); }
};

// "flat", "cheap-mic", "small-speaker"; std::invalid_argument naming the presets otherwise.
FrequencyResponse response_preset(const std::string& name);
std::string response_preset_names();

// A preset's name, breakpoints "100:-3,200:0,10000:-3,16000:-12", or a text file of
// breakpoints (one "Hz dB" or "Hz:dB" pair per line, # comments). std::invalid_argument
// saying what is wrong otherwise.
FrequencyResponse parse_response(const std::string& text);

// Gain in dB at `frequency_hz`, interpolated between the breakpoints as described above.
double response_gain_db(const FrequencyResponse& response, double frequency_hz);

// The linear-phase FIR (kResponseTaps taps; {1} for a flat response).
std::vector<float> response_fir(const FrequencyResponse& response, int sample_rate_hz);

}  // namespace dtmf::sim
