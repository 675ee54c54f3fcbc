#include "frames/stream_trial.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace dtmf::bench {

TrialCounts& TrialCounts::operator+=(const TrialCounts& o) {
  frames += o.frames;
  success += o.success;
  missed += o.missed;
  duplicated += o.duplicated;
  wrong_accepts += o.wrong_accepts;
  check_failed += o.check_failed;
  return *this;
}

TrialCounts run_stream(FrameTrials& trials, const StreamOptions& options, const Channel& channel) {
  const LinkProfile& profile = trials.profile();
  const std::size_t slot = trials.slot_samples();
  const double slot_ms = 1000.0 * static_cast<double>(slot) / profile.sample_rate_hz;

  std::mt19937_64 rng(options.seed);
  std::vector<FrameBits> sent(options.frames);
  std::vector<std::uint32_t> right(options.frames, 0);  // right-bit acceptances per slot
  std::vector<float> clean(slot), heard, pending;
  std::vector<Accepted> accepted;
  FrameReceiver receiver(trials.robot());
  TrialCounts counts;
  counts.frames = options.frames;

  // A frame starts its slot; its estimated start may be a little early (an analysis window
  // centred before the chord already holds some of it) or late by most of the sound (the
  // first windows of a seed chord drowned). So a slot runs from half its silence before
  // its frame to half its silence after: a tail heard in the gap stays with its frame
  // (heard twice), a late detection is not taken for the next slot's.
  const double early_ms =
      0.5 * (slot_ms - 1000.0 * static_cast<double>(trials.sound_samples()) / profile.sample_rate_hz);
  // A microphone whose clock runs off (Doppler, a sound card's crystal) hears the stream
  // stretched or squeezed: 2000 ppm moves a frame 40 ms over a 20 s stream, more than half a
  // fast slot's silence. Its start is mapped back to the sender's time by the ratio the
  // channel itself showed so far (samples given / samples heard).
  std::uint64_t clean_samples = 0, heard_samples = 0;
  auto score = [&] {
    const double sender_per_heard =
        heard_samples > 0 ? static_cast<double>(clean_samples) / static_cast<double>(heard_samples) : 1.0;
    for (const Accepted& a : accepted) {
      const double start_ms = a.start_ms * sender_per_heard;
      const double at = std::floor((start_ms + early_ms) / slot_ms) - static_cast<double>(options.lead_in_slots);
      const auto k = static_cast<std::size_t>(std::max(at, 0.0));
      if (at >= 0 && k < sent.size() && a.bits == sent[k])
        ++right[k];
      else {
        ++counts.wrong_accepts;
        if (std::getenv("DTMF_DEBUG_WRONG")) {
          std::fprintf(stderr,
                       "wrong: start %.1f ms slot %.0f (after the lead-in) bits %llx; sent there %llx, before %llx\n",
                       start_ms, at, (unsigned long long)a.bits.low64(),
                       k < sent.size() ? (unsigned long long)sent[k].low64() : 0ull,
                       k > 0 && k <= sent.size() ? (unsigned long long)sent[k - 1].low64() : 0ull);
        }
      }
    }
    accepted.clear();
  };

  // After the lead-in, slots 0..frames-1 carry a frame; the last one is silence (plus
  // whatever the channel adds).
  const std::size_t lead = options.lead_in_slots;
  for (std::size_t slot_index = 0; slot_index <= lead + options.frames; ++slot_index) {
    std::fill(clean.begin(), clean.end(), 0.0f);
    if (slot_index >= lead && slot_index - lead < options.frames) {
      const std::size_t k = slot_index - lead;
      const link::TransmitFrame frame = trials.random_frame(rng);
      sent[k] = frame.bits;
      FrameTrials::add_frame(frame, clean);
    }
    heard.clear();
    channel(clean, heard);
    clean_samples += clean.size();
    heard_samples += heard.size();
    pending.insert(pending.end(), heard.begin(), heard.end());
    std::size_t at = 0;
    for (; at + options.block_samples <= pending.size(); at += options.block_samples) {
      receiver.feed(std::span<const float>(pending).subspan(at, options.block_samples), accepted);
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(at));
    score();
  }
  if (!pending.empty()) receiver.feed(pending, accepted);
  score();

  for (std::uint32_t r : right) {
    if (r == 1) ++counts.success;
    if (r == 0) ++counts.missed;
    if (r > 1) ++counts.duplicated;
  }
  counts.check_failed = receiver.check_failed();
  return counts;
}

double mean_sound_power(FrameTrials& trials, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<float> slot(trials.slot_samples());
  double sum = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::fill(slot.begin(), slot.end(), 0.0f);
    FrameTrials::add_frame(trials.random_frame(rng), slot);
    for (std::size_t j = 0; j < trials.sound_samples(); ++j) sum += static_cast<double>(slot[j]) * slot[j];
  }
  return sum / static_cast<double>(count * trials.sound_samples());
}

}  // namespace dtmf::bench
