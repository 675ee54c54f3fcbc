// Signal layer: the microphone's spectrum as columns for people to look at (a spectrogram),
// a pull tap in the manner of ggwave's takeRxSpectrum: feed it audio as it is read, take the
// columns that came due.
//
// Every `hop` samples (sample rate / columns_per_s) the last kFftSamples are analysed
// (SpectrumAnalyzer: Hann window, amplitudes where a full-scale sine reads 0 dBFS), and the
// FFT's bins between low_hz and high_hz are gathered into `bins` equal bins, each the loudest
// of those it covers (a tone stays as loud as it is whatever the resolution). Levels in dBFS,
// floored at kFloorDbfs. No clock of its own: a column's time is the audio's.
#pragma once

#include <span>
#include <vector>

#include "signal/spectrum.h"

namespace dtmf::signal {

struct ColumnLevels {
  double end_audio_ms = 0;  // the end of the window it analysed, in ms of audio fed
  std::vector<float> level_dbfs;
};

class SpectrumColumns {
 public:
  static constexpr int kFftSamples = 2048;  // 42.7 ms at 48 kHz: 23.4 Hz bins, finer than any tone step
  static constexpr float kFloorDbfs = -140;

  SpectrumColumns(int sample_rate_hz, double low_hz, double high_hz, int bins, double columns_per_s);
  // The columns that came due within `samples`, oldest first.
  std::vector<ColumnLevels> feed(std::span<const float> samples);

  double low_hz() const { return low_hz_; }
  double step_hz() const { return step_hz_; }
  double window_ms() const { return 1000.0 * kFftSamples / sample_rate_hz_; }

 private:
  ColumnLevels column();

  int sample_rate_hz_;
  double low_hz_;
  double step_hz_;
  int bins_;
  int hop_samples_;
  SpectrumAnalyzer analyzer_;
  std::vector<float> history_;  // the last kFftSamples, oldest first
  std::vector<float> window_;
  std::size_t fed_ = 0;           // samples fed in all
  std::size_t since_column_ = 0;  // samples since the last column
};

}  // namespace dtmf::signal
