// dtmf-bench-talkoff: how often speech, music or noise is taken for a frame or a reply.
//
// Reads audio that carries no frame at all — raw float32 mono at the profile's sample rate
// on stdin (scripts/bench pipes espeak-ng and sox into it), or any file libsndfile reads
// (--wav, resampled) — and feeds it, in 1024-sample blocks as a device would, to
//   - the robot's receiver (link/frame_trials.h): frames that pass the check (the robot
//     would act on them) and frames that fail it (the robot would NACK them);
//   - the sender's reply listener (the adapter's ReplyReceiver): ACKs and NACKs it would hear.
// Every one of them is a false detection; the summary gives each per hour of audio.
// --seconds stops after that much audio (the generator upstream then gets SIGPIPE).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/frame_trials.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "units/decibels.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr std::size_t kBlockSamples = 1024;
constexpr std::size_t kListedMax = 50;  // accepted frames listed one by one in the JSON

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-talkoff: false frames and replies heard in speech, music or noise");
  std::string profile_name = "seed", json_path, wav_path, signal_name = "stdin";
  double max_seconds = 0;
  bool print_rate = false;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  bool authenticated = false;
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--wav", wav_path, "read this file instead of raw float32 on stdin");
  app.add_option("--signal", signal_name, "what the audio is (a label for the report)")->capture_default_str();
  app.add_option("--seconds", max_seconds, "stop after this much audio (0: at the end)")->capture_default_str();
  app.add_flag("--print-sample-rate", print_rate, "print the rate stdin must have, and exit");
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        if (print_rate) {
          std::printf("%d\n", profile.sample_rate_hz);
          return 0;
        }
        std::unique_ptr<physical::WavFileSource> wav;
        if (!wav_path.empty()) wav = std::make_unique<physical::WavFileSource>(wav_path, profile.sample_rate_hz);
        const auto max_samples = static_cast<std::uint64_t>(max_seconds * profile.sample_rate_hz);

        FrameTrials trials(profile, bench_key(authenticated));
        FrameReceiver robot(trials.robot());
        const auto sender = link::make_link(profile, [&] {
          link::LinkOptions o;
          o.key = trials.robot().options().key;
          return o;
        }());
        ReplyReceiver replies(*sender);
        std::vector<Accepted> accepted;
        std::uint64_t samples = 0;
        double sum_squares = 0, peak = 0;
        std::vector<float> block(kBlockSamples);
        while (max_samples == 0 || samples < max_samples) {
          std::size_t want = kBlockSamples;
          if (max_samples != 0) want = static_cast<std::size_t>(std::min<std::uint64_t>(want, max_samples - samples));
          const std::size_t got = wav ? wav->read(std::span<float>(block).first(want))
                                      : std::fread(block.data(), sizeof(float), want, stdin);
          if (got == 0) break;
          const std::span<const float> heard(block.data(), got);
          for (float x : heard) {
            sum_squares += static_cast<double>(x) * x;
            peak = std::max(peak, static_cast<double>(std::fabs(x)));
          }
          robot.feed(heard, accepted);
          replies.feed(heard);
          samples += got;
        }
        if (samples == 0) throw std::runtime_error("no audio read");
        const std::uint64_t acks = replies.acks(), nacks = replies.nacks(), confirmations = replies.confirmations();
        const double hours = static_cast<double>(samples) / profile.sample_rate_hz / 3600.0;
        const double rms_dbfs = units::db_from_power_ratio(sum_squares / static_cast<double>(samples) + 1e-30);
        const auto per_hour = [&](std::uint64_t n) { return static_cast<double>(n) / hours; };
        std::printf(
            "talk-off  %-6s %-8s %7.2f h (RMS %6.1f dBFS, peak %5.2f): accepted %llu (%.2f/h), "
            "check-failing %llu (%.2f/h), refused %llu (%.2f/h), ACK %llu (%.2f/h), NACK %llu (%.2f/h), "
            "false confirmations %llu (%.2f/h)\n",
            profile.name.c_str(), signal_name.c_str(), hours, rms_dbfs, peak,
            static_cast<unsigned long long>(accepted.size()), per_hour(accepted.size()),
            static_cast<unsigned long long>(robot.check_failed()), per_hour(robot.check_failed()),
            static_cast<unsigned long long>(robot.refused()), per_hour(robot.refused()),
            static_cast<unsigned long long>(acks), per_hour(acks), static_cast<unsigned long long>(nacks),
            per_hour(nacks), static_cast<unsigned long long>(confirmations), per_hour(confirmations));

        nlohmann::json listed = nlohmann::json::array();
        for (std::size_t i = 0; i < std::min(accepted.size(), kListedMax); ++i) {
          listed.push_back({{"start_ms", accepted[i].start_ms}, {"bits", accepted[i].bits.decimal()}});
        }
        write_json(json_path, {{"benchmark", "talkoff"},
                               {"profile", profile.name},
                               {"authenticated", authenticated},
                               {"signal", signal_name},
                               {"audio_s", static_cast<double>(samples) / profile.sample_rate_hz},
                               {"hours", hours},
                               {"rms_dbfs", rms_dbfs},
                               {"peak", peak},
                               {"accepted", accepted.size()},
                               {"accepted_per_hour", per_hour(accepted.size())},
                               {"check_failed", robot.check_failed()},
                               {"check_failed_per_hour", per_hour(robot.check_failed())},
                               {"acks", acks},
                               {"acks_per_hour", per_hour(acks)},
                               {"nacks", nacks},
                               {"nacks_per_hour", per_hour(nacks)},
                               {"refused", robot.refused()},
                               {"refused_per_hour", per_hour(robot.refused())},
                               {"false_confirmations", confirmations},
                               {"false_confirmations_per_hour", per_hour(confirmations)},
                               {"accepted_frames", listed}});
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-talkoff: %s\n", why.c_str()); });
}
