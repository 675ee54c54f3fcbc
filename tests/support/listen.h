// Test helpers: push audio through the robot's or the sender's listener in hop-sized blocks
// (as a live device would deliver it) and collect what passes.
#pragma once

#include <span>
#include <vector>

#include "link/seed_receiver_path.h"
#include "signal/tone_listener.h"
#include "sim/acoustic_channel.h"

namespace dtmf::test_support {

template <class Listener>
std::vector<signal::Heard> listen(Listener& listener, std::span<const float> audio, std::size_t block = 2400) {
  std::vector<signal::Heard> heard;
  for (std::size_t i = 0; i < audio.size(); i += block) {
    const auto part = audio.subspan(i, std::min(block, audio.size() - i));
    for (const signal::Heard& h : listener.feed(part)) heard.push_back(h);
  }
  return heard;
}

inline std::vector<link::SeedReceivedFrame> receive(const LinkProfile& profile, std::span<const float> audio) {
  link::SeedReceiverPath receiver(profile);
  std::vector<link::SeedReceivedFrame> frames;
  for (std::size_t i = 0; i < audio.size(); i += 2400) {
    const auto part = audio.subspan(i, std::min<std::size_t>(2400, audio.size() - i));
    for (const auto& f : receiver.feed(part)) frames.push_back(f);
  }
  return frames;
}

// `audio` as heard through a channel with one loudspeaker at `distance_m`, plus `tail_ms`
// of the room after the audio ends.
inline std::vector<float> through_channel(std::span<const float> audio, int rate, double distance_m,
                                          const sim::ChannelConfig& config = {}, double tail_ms = 100) {
  sim::AcousticChannel channel(rate, config);
  channel.add_transmitter(distance_m);
  std::vector<float> padded(audio.begin(), audio.end());
  padded.resize(padded.size() + static_cast<std::size_t>(tail_ms * rate / 1000), 0.0f);
  std::vector<float> out;
  out.reserve(padded.size());
  channel.process(padded, out);
  return out;
}

}  // namespace dtmf::test_support
