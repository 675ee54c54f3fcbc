// dtmf-bench-lost: why frames of a hopped profile are lost in white noise, frame by frame.
//
// Each random frame sounds alone in a stream (300 ms of the noise before and after it) at one
// SNR, defined as dtmf-bench-snr defines it; the robot's receiver (a fresh one per frame) says
// whether it was accepted. For every lost frame the listener's readings are taken apart
// against the symbols sent: the two-chord reading near its start (any offset hypothesis, or a
// whole-chord re-read) that holds the fewest errors counts (2 × misread + unheard), and the
// frame is put down to
//   - the gate: no two-chord reading began within a hop of it;
//   - its tones: e heard tones misread, s unheard; of the misread ones, how many had the sent
//     tone as their band's runner-up (what the Chase swaps can mend) and how many were among
//     the profile's `chase_tones` least certain heard tones; and whether an oracle that erased
//     exactly the misread and unheard tones, no more than the plain tries may (e + s ≤ 4), would
//     have decoded it: the most any erasure decoder could win back from these readings.
// Only profiles with hopped frames (`fast`); prints a summary, --json writes it.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "common/bench_report.h"
#include "common/gaussian.h"
#include "frames/stream_trial.h"
#include "program_main.h"
#include "reliability/command_frame.h"
#include "signal/hop_listener.h"
#include "units/decibels.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr int kCodeTones = reliability::kCodeSymbols;  // a two-chord frame's tones
constexpr double kLeadMs = 300;                        // the noise alone before and after the frame

struct Autopsy {
  int doubted = 0;       // the profile's chase_tones: the least certain tones the swaps try
  int max_erasures = 0;  // the profile's: all its parity but the symbols a plain try keeps
  std::uint64_t frames = 0, accepted = 0, no_reading = 0;
  std::map<std::pair<int, int>, std::uint64_t> by_misread_unheard;
  std::uint64_t misread = 0, runner_up_right = 0, among_doubted = 0, oracle_decodes = 0;
  std::array<std::uint64_t, kCodeTones> misread_by_rank{};  // 0: the least certain heard tone

  void lost(const signal::HopCandidate& c, const reliability::CodeSymbols& sent) {
    std::vector<std::pair<float, int>> heard;  // certainty, tone
    int unheard = 0;
    for (int t = 0; t < kCodeTones; ++t) {
      if (c.tones[t].heard && c.tones[t].risen)
        heard.push_back({c.tones[t].certainty, t});
      else
        ++unheard;
    }
    std::sort(heard.begin(), heard.end());
    int wrong = 0;
    for (std::size_t rank = 0; rank < heard.size(); ++rank) {
      const int t = heard[rank].second;
      if (c.tones[t].symbol == sent[t]) continue;
      ++wrong;
      ++misread_by_rank[rank];
      among_doubted += static_cast<int>(rank) < doubted ? 1 : 0;
      runner_up_right += c.tones[t].runner_up == sent[t] ? 1 : 0;
    }
    misread += wrong;
    ++by_misread_unheard[{wrong, unheard}];
    oracle_decodes += wrong + unheard <= max_erasures ? 1 : 0;
  }
};

int errors_of(const signal::HopCandidate& c, const reliability::CodeSymbols& sent) {
  int cost = 0;
  for (int t = 0; t < kCodeTones; ++t) {
    if (!c.tones[t].heard || !c.tones[t].risen)
      cost += 1;
    else if (c.tones[t].symbol != sent[t])
      cost += 2;
  }
  return cost;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-lost: why frames are lost in white noise, frame by frame (hopped profiles)");
  std::string profile_name = "fast", json_path;
  double snr_db = -12;
  std::size_t frames = 1000;
  std::uint64_t seed = 1;
  app.add_option("--profile", profile_name, "a profile with hopped frames")->capture_default_str();
  app.add_option("--snr-db", snr_db, "SNR as dtmf-bench-snr defines it")->capture_default_str();
  app.add_option("--frames", frames, "frames, each alone in its stream")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "frames and noise")->capture_default_str();
  app.add_option("--json", json_path, "write the results to this JSON file");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        if (!std::holds_alternative<HopPlan>(profile.plan)) {
          throw std::invalid_argument("profile " + profile.name + " has no hopped frames to take apart; use fast");
        }
        FrameTrials trials(profile);
        const double signal_power = mean_sound_power(trials, 256, seed);
        const auto sigma = static_cast<float>(std::sqrt(signal_power / units::power_ratio_from_db(snr_db)));
        const auto lead = static_cast<std::size_t>(kLeadMs * profile.sample_rate_hz / 1000);
        std::mt19937_64 rng(seed);
        GaussianNoise noise(seed);
        Autopsy a;
        a.doubted = profile.hops().chase_tones;
        a.max_erasures = profile.hops().max_erasures;
        // "Near its start": within a hop (a start the grid guessed lies up to a hop off) and 2 ms.
        const double near_ms = 1000.0 * profile.hops().hop_samples / profile.sample_rate_hz + 2;
        for (std::size_t i = 0; i < frames; ++i) {
          const link::TransmitFrame frame = trials.random_frame(rng);
          std::vector<float> stream(lead + frame.audio.size() + lead, 0.0f);
          std::copy(frame.audio.begin(), frame.audio.end(), stream.begin() + static_cast<std::ptrdiff_t>(lead));
          noise.add_to(stream, sigma);
          FrameReceiver receiver(trials.robot());
          std::vector<Accepted> accepted;
          receiver.feed(stream, accepted);
          ++a.frames;
          if (std::any_of(accepted.begin(), accepted.end(), [&](const Accepted& x) { return x.bits == frame.bits; })) {
            ++a.accepted;
            continue;
          }
          signal::HopListener listener(profile);
          const auto sent = reliability::command_frame_symbols(frame.bits.low64());
          const signal::HopCandidate* best = nullptr;
          for (const auto& c : listener.feed(stream)) {
            if (c.chords != 2 || std::abs(c.start_ms - kLeadMs) > near_ms) continue;
            if (!best || errors_of(c, sent) < errors_of(*best, sent)) best = &c;
          }
          if (best)
            a.lost(*best, sent);
          else
            ++a.no_reading;
        }
        const std::uint64_t lost = a.frames - a.accepted;
        const auto pct = [&](std::uint64_t n, std::uint64_t of) { return of ? 100.0 * n / of : 0.0; };
        std::printf("dtmf-bench-lost: profile %s at %.1f dB SNR, %llu frames alone in noise\n", profile.name.c_str(),
                    snr_db, static_cast<unsigned long long>(a.frames));
        std::printf("accepted %.2f %%; lost %llu: %llu with no reading at the gate, %llu read with errors\n",
                    pct(a.accepted, a.frames), static_cast<unsigned long long>(lost),
                    static_cast<unsigned long long>(a.no_reading),
                    static_cast<unsigned long long>(lost - a.no_reading));
        std::printf(
            "their misread heard tones: %llu; the runner-up was the tone sent for %.0f %%, %.0f %% were among the "
            "%d least certain\n",
            static_cast<unsigned long long>(a.misread), pct(a.runner_up_right, a.misread),
            pct(a.among_doubted, a.misread), a.doubted);
        std::printf(
            "an oracle erasing exactly the misread and unheard tones (at most %d, as the plain tries) would decode "
            "%llu of them: "
            "%.2f %% at most\n",
            a.max_erasures, static_cast<unsigned long long>(a.oracle_decodes),
            pct(a.accepted + a.oracle_decodes, a.frames));
        nlohmann::json by = nlohmann::json::array();
        for (const auto& [es, n] : a.by_misread_unheard)
          by.push_back({{"misread", es.first}, {"unheard", es.second}, {"frames", n}});
        write_json(json_path, {{"benchmark", "lost"},
                               {"profile", profile.name},
                               {"snr_db", snr_db},
                               {"seed", seed},
                               {"frames", a.frames},
                               {"accepted", a.accepted},
                               {"success_rate", static_cast<double>(a.accepted) / static_cast<double>(a.frames)},
                               {"lost_no_reading", a.no_reading},
                               {"lost_by_misread_and_unheard", by},
                               {"misread_tones", a.misread},
                               {"misread_runner_up_right", a.runner_up_right},
                               {"misread_among_doubted", a.among_doubted},
                               {"misread_by_certainty_rank", a.misread_by_rank},
                               {"doubted_tones", a.doubted},
                               {"oracle_max_erasures", a.max_erasures},
                               {"oracle_erasure_decodes", a.oracle_decodes}});
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-lost: %s\n", why.c_str()); });
}
