// Test helper: a recording of the PulseAudio air (parecord on air.monitor, a third-party
// recorder) made while a test runs, and the chords in it that the air itself cut in two.
//
// Why: a seed chord is 0.8 s of steady tones. When the machine cannot feed the sound server
// in time (a starved or paused virtual machine), PulseAudio plays silence in the middle of
// the chord (an underrun) and the rest of the chord after it. A seed frame has no sequence
// number to tell that second piece from a new chord: the receiver tells them apart by
// length, for holes up to debounce.max_dropout_ms (signal/debouncer.h). A test that counts
// extra receptions must know how many chords the air split, and how: the recording shows
// it, sample by sample.
//
// How: 10 ms Hann-windowed frames; a frame is "on" when its energy between low_hz and
// high_hz is within 30 dB of one tone at the seed's amplitude (the air is otherwise digital
// silence, and ACK tones lie below the band). A chord the air split is an on-run shorter
// than the chord, then silence, then an on-run that makes up the rest of it (40 ms or more:
// the next chord may follow at once).
#pragma once

#include <signal.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "physical/wav_file.h"
#include "sim/real_fft.h"
#include "support/processes.h"

namespace dtmf::test_support {

struct SplitChord {
  double start_s;    // in the recording
  double first_ms;   // the piece before the silence
  double gap_ms;     // the silence the air put in
  double second_ms;  // the rest of the chord
};

// The longest silence inside a chord that find_split_chords looks for; a piece shorter than
// a chord only comes from a split, so a long limit finds no false ones.
inline constexpr double kLongestHoleMs = 2000;

// Every chord of chord_ms in `audio` that silence cut in two (see the top of this file).
inline std::vector<SplitChord> find_split_chords(const std::vector<float>& audio, int rate_hz, double chord_ms,
                                                 double low_hz, double high_hz) {
  const auto frame = static_cast<std::size_t>(rate_hz / 100);  // 10 ms
  sim::RealFft fft(frame);
  sim::FftReal in(frame);
  sim::FftBins out(fft.bins());
  std::vector<float> window(frame);
  for (std::size_t i = 0; i < frame; ++i)
    window[i] = static_cast<float>(0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / frame));
  const double tone_power = std::pow(0.2 * static_cast<double>(frame) / 4.0, 2);  // a 0.2-amplitude tone, Hann window
  const double bin_hz = static_cast<double>(rate_hz) / static_cast<double>(frame);

  std::vector<bool> on;
  for (std::size_t at = 0; at + frame <= audio.size(); at += frame) {
    for (std::size_t i = 0; i < frame; ++i) in[i] = audio[at + i] * window[i];
    fft.forward(in.data(), out.data());
    double power = 0;
    for (auto b = static_cast<std::size_t>(low_hz / bin_hz); b <= high_hz / bin_hz && b < out.size(); ++b)
      power += std::norm(out[b]);
    on.push_back(power > tone_power * 1e-3);
  }
  struct Run {
    std::size_t start, frames;
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < on.size(); ++i) {
    if (!on[i]) continue;
    if (!runs.empty() && runs.back().start + runs.back().frames == i)
      ++runs.back().frames;
    else
      runs.push_back({i, 1});
  }
  std::vector<SplitChord> split;
  for (std::size_t r = 0; r + 1 < runs.size(); ++r) {
    const double first_ms = 10.0 * static_cast<double>(runs[r].frames);
    const double second_ms = 10.0 * static_cast<double>(runs[r + 1].frames);
    const double gap_ms = 10.0 * static_cast<double>(runs[r + 1].start - runs[r].start - runs[r].frames);
    // The rest may run straight into the next chord: a sender that lost the time of the
    // silence plays its next chord without the gap. Holes up to kLongestHoleMs are found,
    // beyond what the receiver bridges, so that a test can tell the two kinds apart.
    if (first_ms < chord_ms - 30 && gap_ms < kLongestHoleMs && first_ms + second_ms >= chord_ms - 40) {
      split.push_back({static_cast<double>(runs[r].start) / 100.0, first_ms, gap_ms, second_ms});
      ++r;
    }
  }
  return split;
}

// How many of `split` have a hole longer than `bridged_ms` (a receiver's max_dropout_ms):
// each such chord may be heard twice by a receiver without sequence numbers.
inline long holes_longer_than(const std::vector<SplitChord>& split, double bridged_ms) {
  long count = 0;
  for (const SplitChord& s : split) count += s.gap_ms > bridged_ms;
  return count;
}

class AirRecording {
 public:
  // `monitor`: the sink to record, as PulseAudio names its monitor source.
  explicit AirRecording(std::string wav_path, const std::string& monitor = "air.monitor") : path_(std::move(wav_path)) {
    pid_ = start_process("parecord --device=" + monitor +
                             " --rate=48000 --channels=1 --format=float32le "
                             "--file-format=wav " +
                             path_,
                         path_ + ".log");
  }
  ~AirRecording() { stop(); }
  AirRecording(const AirRecording&) = delete;
  AirRecording& operator=(const AirRecording&) = delete;

  // Stops the recorder (SIGINT: parecord then writes the WAV header's lengths).
  void stop() {
    if (pid_ > 0) stop_process(pid_, SIGINT);
    pid_ = 0;
  }

  // Stops the recording and returns every chord of chord_ms that the air split.
  std::vector<SplitChord> split_chords(double chord_ms, double low_hz, double high_hz) {
    stop();
    return find_split_chords(physical::read_audio_file(path_, 48000), 48000, chord_ms, low_hz, high_hz);
  }

 private:
  std::string path_;
  int pid_ = 0;
};

}  // namespace dtmf::test_support
