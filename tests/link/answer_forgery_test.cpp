// A forger beside the sender's microphone plays random tagged ACKs, back to back in the reply
// lane of the frame the sender waits for (the lane is public: the frame's counter is on the
// air), for ten minutes of audio against a keyed sender that sends all the while, each
// transmission waiting 500 ms for its answer. The robot never answers. No transmission may be
// confirmed, and the forger must have been heard: its readings are counted as guesses, at
// most kTagGuessesPerAttempt a transmission (docs/security.md has the bound: 1.0e-6 a guess).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include "link/answer_wait.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "reliability/reply_code.h"
#include "security/link_key.h"
#include "signal/hop_synthesizer.h"
#include "sim/noise.h"

using namespace dtmf;

TEST(AnswerForgery, TenMinutesOfRandomTagsConfirmNothing) {
  const LinkProfile& p = profile_by_name("fast");
  std::array<unsigned char, security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(0x3c ^ (29 * i));
  link::LinkOptions options;
  options.key = security::LinkKey::from_bytes(bytes);
  const auto sender = link::make_link(p, options);
  const auto ear = sender->answer_listener();

  constexpr double kAudioS = 600;
  const auto transmission = static_cast<std::size_t>(p.sample_rate_hz * p.timing.ack_timeout_ms / 1000.0);
  const auto transmissions = static_cast<int>(kAudioS * p.sample_rate_hz / static_cast<double>(transmission));
  std::mt19937 rng(35);
  sim::NoiseSource noise(sim::parse_noise("pink", -50), p.sample_rate_hz, 35);
  std::vector<float> forged;  // what the forger has queued and not yet played
  long confirmations = 0, guesses = 0, most_guesses = 0;
  const auto block = static_cast<std::size_t>(sender->answer_block_samples());
  for (int t = 0; t < transmissions; ++t) {
    const link::TransmitFrame frame = sender->random_frame(static_cast<std::uint64_t>(t) + 1);
    link::AnswerWait wait(*sender, frame);
    std::vector<float> air(transmission, 0.0f);
    std::size_t at = 0;
    while (at < air.size()) {
      if (forged.empty()) {
        const std::uint32_t tag = rng() % reliability::kReplyTagSpace;
        forged = signal::synthesize_hopped_reply(p, reliability::tag_tones(tag), frame.answer_lane);
      }
      const std::size_t n = std::min(forged.size(), air.size() - at);
      std::copy_n(forged.begin(), n, air.begin() + static_cast<long>(at));
      forged.erase(forged.begin(), forged.begin() + static_cast<long>(n));
      at += n;
    }
    noise.add_to(air);
    for (std::size_t i = 0; i < air.size(); i += block) {
      for (const link::Answer& a : ear->feed(std::span<const float>(air).subspan(i, std::min(block, air.size() - i)))) {
        if (a.ack && wait.answered_by(a)) ++confirmations;
      }
    }
    guesses += wait.guesses();
    most_guesses = std::max<long>(most_guesses, wait.guesses());
  }
  std::printf(
      "[ figures  ] %d transmissions of %.0f ms, %ld guesses (%.1f a transmission, at most %ld), %ld confirmed\n",
      transmissions, p.timing.ack_timeout_ms, guesses, static_cast<double>(guesses) / transmissions, most_guesses,
      confirmations);
  EXPECT_EQ(confirmations, 0);
  EXPECT_LE(most_guesses, reliability::kTagGuessesPerAttempt);
  // The forger was heard: most transmissions spent their whole budget on its tags.
  EXPECT_GE(guesses, static_cast<long>(transmissions) * reliability::kTagGuessesPerAttempt * 3 / 4);
}
