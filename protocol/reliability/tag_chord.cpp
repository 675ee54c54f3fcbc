#include "reliability/tag_chord.h"

#include <algorithm>
#include <bit>

namespace dtmf::reliability {

BandValueSet tag_chord_taken(std::span<const std::uint8_t> frame_symbols) {
  constexpr std::size_t kBandsPerSet = kTagChordTones / 2;
  BandValueSet taken{};
  for (std::size_t t = 0; t < frame_symbols.size(); ++t) {
    const std::size_t chord = t / kBandsPerSet, band = t % kBandsPerSet;
    const std::uint32_t value = 1u << frame_symbols[t];
    taken[(chord % 2) * kBandsPerSet + band] |= value | (value << 1) | (value >> 1);
  }
  return taken;
}

TagChordSymbols tag_chord_symbols(const TagBytes& tag, const BandValueSet& taken) {
  TagChordSymbols symbols{};
  for (std::size_t k = 0; k < kTagChordTones; ++k) {
    const int free_values = kTagChordValues - std::popcount(taken[k]);
    int n = tag[k] % free_values;
    for (int v = 0; v < kTagChordValues; ++v) {
      if ((taken[k] >> v) & 1u) continue;
      if (n-- == 0) {
        symbols[k] = static_cast<std::uint8_t>(v);
        break;
      }
    }
  }
  return symbols;
}

namespace {

// Band k's reading at one hypothesis: its most risen tone the sender did not send, or -1.
int band_reading(const std::array<std::int8_t, kTagChordCandidates>& candidates, std::uint32_t set_aside) {
  for (const std::int8_t v : candidates) {
    if (v < 0) return -1;
    if (((set_aside >> v) & 1u) == 0) return v;
  }
  return -1;
}

}  // namespace

int tag_chord_matches(const TagChordReading& reading, const TagChordSymbols& tag, const BandValueSet& set_aside) {
  int best = 0;
  for (const auto& hypothesis : reading) {
    int matches = 0;
    for (std::size_t k = 0; k < kTagChordTones; ++k) {
      // A band whose symbol the sender sent itself is left unread: its own tail sits there.
      if ((set_aside[k] >> tag[k]) & 1u) continue;
      matches += band_reading(hypothesis[k], set_aside[k]) == tag[k] ? 1 : 0;
    }
    best = std::max(best, matches);
  }
  return best;
}

bool spells_tag_chord(const TagChordReading& reading, const TagChordSymbols& tag, const BandValueSet& set_aside) {
  return tag_chord_matches(reading, tag, set_aside) >= kTagChordMatchesNeeded;
}

namespace {
int heard_at(const std::array<std::array<std::int8_t, kTagChordCandidates>, kTagChordTones>& hypothesis) {
  return static_cast<int>(std::count_if(hypothesis.begin(), hypothesis.end(), [](const auto& c) { return c[0] >= 0; }));
}
}  // namespace

int tag_chord_heard(const TagChordReading& reading) {
  int best = 0;
  for (const auto& hypothesis : reading) best = std::max(best, heard_at(hypothesis));
  return best;
}

std::array<int, kTagChordTones> tag_chord_plain(const TagChordReading& reading) {
  const auto most = std::max_element(reading.begin(), reading.end(),
                                     [](const auto& a, const auto& b) { return heard_at(a) < heard_at(b); });
  std::array<int, kTagChordTones> plain{};
  for (std::size_t k = 0; k < kTagChordTones; ++k) plain[k] = (*most)[k][0];
  return plain;
}

}  // namespace dtmf::reliability
