// A forger beside the sender's microphone plays tag chords back to back, each band at a value
// the frame on air left free (the frame is public), for ten minutes of audio against a keyed
// sender that sends all the while, each transmission waiting 500 ms for its answer. At the
// end of every tenth transmission the forger stops and the robot's true tag chord sounds.
// No forged chord may confirm a transmission, the forger must have been heard (its chords
// read as tag chords), and every true answer must still confirm its frame: there is no
// budget of guesses to spend (docs/security.md: 9.4e-9 a reading).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include "link/answer_wait.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/tag_chord.h"
#include "security/link_key.h"
#include "signal/hop_synthesizer.h"
#include "sim/noise.h"
#include "support/test_key.h"

using namespace dtmf;

TEST(AnswerForgery, TenMinutesOfForgedTagChordsConfirmNothingAndTheTrueAnswerIsStillHeard) {
  const LinkProfile& p = profile_by_name("fast");
  link::LinkOptions options;
  options.key = test_support::test_key(0x3c);
  const auto sender = link::make_link(p, options);
  const auto robot = link::make_link(p, options);
  const auto ear = sender->answer_listener();

  constexpr double kAudioS = 600;
  constexpr int kTrueAnswerEvery = 10;
  const auto transmission = static_cast<std::size_t>(p.sample_rate_hz * p.timing.ack_timeout_ms / 1000.0);
  const auto transmissions = static_cast<int>(kAudioS * p.sample_rate_hz / static_cast<double>(transmission));
  std::mt19937 rng(35);
  sim::NoiseSource noise(sim::parse_noise("pink", -50), p.sample_rate_hz, 35);
  std::vector<float> forged;  // what the forger has queued and not yet played
  long forged_confirmations = 0, readings = 0, forged_chords = 0;
  int true_answers = 0, true_heard = 0;
  const auto block = static_cast<std::size_t>(sender->answer_block_samples());
  for (int t = 0; t < transmissions; ++t) {
    const link::TransmitFrame frame = sender->random_frame(static_cast<std::uint64_t>(t) + 1);
    link::AnswerWait wait(*sender, frame);
    std::vector<float> air(transmission, 0.0f);
    const bool answered = t % kTrueAnswerEvery == kTrueAnswerEvery - 1;
    std::vector<float> truth;
    if (answered) {
      link::Reception r = link::intact_reception(frame);
      r.heard_ms = 1e9;  // no silence before it: it sounds where the forger stops
      truth = robot->answer_audio(r);
    }
    const std::size_t forger_until = air.size() - truth.size();
    std::size_t at = 0;
    while (at < forger_until) {
      if (forged.empty()) {
        reliability::TagBytes guess{};
        for (auto& b : guess) b = static_cast<std::uint8_t>(rng());
        forged = signal::synthesize_tag_chord(p, reliability::tag_chord_symbols(guess, frame.sent_tones));
        ++forged_chords;
      }
      const std::size_t n = std::min(forged.size(), forger_until - at);
      std::copy_n(forged.begin(), n, air.begin() + static_cast<long>(at));
      forged.erase(forged.begin(), forged.begin() + static_cast<long>(n));
      at += n;
    }
    std::copy(truth.begin(), truth.end(), air.begin() + static_cast<long>(forger_until));
    forged.clear();  // the forger's chord cut off where the truth begins
    noise.add_to(air);
    bool confirmed = false;
    for (std::size_t i = 0; i < air.size(); i += block) {
      for (const link::Answer& a : ear->feed(std::span<const float>(air).subspan(i, std::min(block, air.size() - i)))) {
        readings += a.tag_reading ? 1 : 0;
        if (!a.ack || !wait.answered_by(a)) continue;
        const double in_transmission_ms =
            a.heard_ms - 1000.0 * static_cast<double>(t) * static_cast<double>(transmission) / p.sample_rate_hz;
        const double truth_from_ms = 1000.0 * static_cast<double>(forger_until) / p.sample_rate_hz;
        if (answered && in_transmission_ms > truth_from_ms) {
          confirmed = true;
        } else {
          ++forged_confirmations;
        }
      }
    }
    true_answers += answered ? 1 : 0;
    true_heard += confirmed ? 1 : 0;
  }
  std::printf(
      "[ figures  ] %d transmissions of %.0f ms, %ld forged chords, %ld tag readings, %ld forged confirmations; "
      "%d of %d true answers heard after the forger\n",
      transmissions, p.timing.ack_timeout_ms, forged_chords, readings, forged_confirmations, true_heard, true_answers);
  EXPECT_EQ(forged_confirmations, 0);
  // The forger was heard: most of its chords were read as tag chords.
  EXPECT_GE(readings, forged_chords * 3 / 4);
  EXPECT_EQ(true_heard, true_answers);
}
