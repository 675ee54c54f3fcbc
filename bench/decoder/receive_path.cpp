// dtmf-bench-receive: the robot's whole receive path as dtmf-agent runs it, and the sender's
// answer ear the same way, in seconds of audio per second of one core's CPU time
// (CLOCK_THREAD_CPUTIME_ID).
//
// The robot listens with every link profile at once (robot_agent/agent.cpp): every profile's
// receiver gets the same audio, in blocks of the smallest receiver block. The sender's ear is
// measured the same way: every profile's answer listener on the same audio. Signals:
//   robot noise:   pink noise at -30 dBFS, nothing to find (the robot's usual day);
//   robot frames:  every profile's random frames in turn, back to back (each with its gap),
//                  in pink noise at -40 dBFS; each receiver must accept all of its own
//                  profile's frames, or the figure would flatter; anything more it accepts (a
//                  frame read from another profile's chords) is counted and reported;
//   ear noise:     the same noise;
//   ear answers:   every profile's answers (the robot's ACKs to those frames) in turn, each
//                  followed by its profile's frame slot of silence (a sender's cadence), in the
//                  same noise; each ear must hear at least its own answers.
// Answers heard in noise, like extra frames, are reported, not refused: they are findings.
// Prints one line per signal; --json PATH writes them.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <random>

#include "common/bench_report.h"
#include "common/thread_cpu.h"
#include "frames/frame_trials.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "sim/noise.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr double kNoiseOnlyDbfs = -30;
constexpr double kUnderFramesDbfs = -40;

struct Signal {
  std::vector<float> audio;
  std::vector<std::size_t> expected;  // per profile, in all_profiles() order
};

void add_noise(std::vector<float>& audio, double dbfs, int sample_rate_hz, unsigned seed) {
  sim::NoiseSource(sim::parse_noise("pink", dbfs), sample_rate_hz, seed).add_to(audio);
}

// Every profile's frames in turn, as many rounds as fit in `audio_s` (at least one).
Signal frames_in_turn(std::vector<std::unique_ptr<FrameTrials>>& trials, double audio_s, int rate_hz) {
  std::size_t round_samples = 0;
  for (const auto& t : trials) round_samples += t->slot_samples();
  const std::size_t rounds = std::max<std::size_t>(1, static_cast<std::size_t>(audio_s * rate_hz) / round_samples);
  Signal s{std::vector<float>(rounds * round_samples, 0.0f), std::vector<std::size_t>(trials.size(), rounds)};
  std::mt19937_64 rng(7);
  std::size_t at = 0;
  for (std::size_t r = 0; r < rounds; ++r) {
    for (auto& t : trials) {
      FrameTrials::add_frame(t->random_frame(rng), std::span<float>(s.audio).subspan(at));
      at += t->slot_samples();
    }
  }
  add_noise(s.audio, kUnderFramesDbfs, rate_hz, 2);
  return s;
}

// The robot's answers to every profile's frames, in turn, each followed by its frame slot.
Signal answers_in_turn(std::vector<std::unique_ptr<FrameTrials>>& trials, double audio_s, int rate_hz) {
  std::vector<std::vector<std::vector<float>>> answers;  // per profile: one round's answers
  std::mt19937_64 rng(11);
  for (auto& t : trials) {
    std::vector<float> frame(t->slot_samples(), 0.0f);
    FrameTrials::add_frame(t->random_frame(rng), frame);
    Responder robot(t->robot());
    answers.push_back(robot.feed(frame));
  }
  std::size_t round_samples = 0;
  for (std::size_t p = 0; p < answers.size(); ++p)
    for (const auto& a : answers[p]) round_samples += a.size() + trials[p]->slot_samples();
  const std::size_t rounds =
      std::max<std::size_t>(1, static_cast<std::size_t>(audio_s * rate_hz) / std::max<std::size_t>(1, round_samples));
  Signal s{std::vector<float>(rounds * round_samples, 0.0f), std::vector<std::size_t>(trials.size(), 0)};
  std::size_t at = 0;
  for (std::size_t r = 0; r < rounds; ++r) {
    for (std::size_t p = 0; p < answers.size(); ++p) {
      for (const auto& a : answers[p]) {
        std::copy(a.begin(), a.end(), s.audio.begin() + static_cast<std::ptrdiff_t>(at));
        at += a.size() + trials[p]->slot_samples();
        ++s.expected[p];
      }
    }
  }
  add_noise(s.audio, kUnderFramesDbfs, rate_hz, 3);
  return s;
}

struct Measurement {
  double audio_s = 0;
  double cpu_s = 0;
  std::vector<std::size_t> heard;  // per profile
};

Measurement robot_path(std::vector<std::unique_ptr<FrameTrials>>& trials, const std::vector<float>& audio,
                       std::size_t block, int rate_hz) {
  std::vector<FrameReceiver> receivers;
  for (auto& t : trials) receivers.emplace_back(t->robot());
  std::vector<std::vector<Accepted>> accepted(trials.size());
  for (auto& a : accepted) a.reserve(audio.size() / 1000);
  const double start = thread_cpu_s();
  for (std::size_t at = 0; at < audio.size(); at += block) {
    const auto samples = std::span<const float>(audio).subspan(at, std::min(block, audio.size() - at));
    for (std::size_t p = 0; p < receivers.size(); ++p) receivers[p].feed(samples, accepted[p]);
  }
  Measurement m{static_cast<double>(audio.size()) / rate_hz, thread_cpu_s() - start, {}};
  for (const auto& a : accepted) m.heard.push_back(a.size());
  return m;
}

Measurement answer_ear(std::vector<std::unique_ptr<link::Link>>& senders, const std::vector<float>& audio,
                       std::size_t block, int rate_hz) {
  std::vector<std::unique_ptr<ReplyReceiver>> ears;
  for (auto& s : senders) ears.push_back(std::make_unique<ReplyReceiver>(*s));
  const double start = thread_cpu_s();
  for (std::size_t at = 0; at < audio.size(); at += block) {
    const auto samples = std::span<const float>(audio).subspan(at, std::min(block, audio.size() - at));
    for (auto& ear : ears) ear->feed(samples);
  }
  Measurement m{static_cast<double>(audio.size()) / rate_hz, thread_cpu_s() - start, {}};
  for (const auto& ear : ears) m.heard.push_back(ear->acks());
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "dtmf-bench-receive: the robot's receive path and the sender's answer ear, every profile at once, "
      "seconds of audio per CPU second");
  std::string json_path;
  double audio_s = 60;
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--audio-s", audio_s, "seconds of audio per signal")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        std::vector<std::unique_ptr<FrameTrials>> trials;
        std::vector<std::unique_ptr<link::Link>> senders;
        std::size_t robot_block = SIZE_MAX, ear_block = SIZE_MAX;
        std::string names;
        const int rate_hz = all_profiles().front()->sample_rate_hz;
        for (const LinkProfile* p : all_profiles()) {
          if (p->sample_rate_hz != rate_hz) throw std::runtime_error("profiles at different rates: " + p->name);
          trials.push_back(std::make_unique<FrameTrials>(*p));
          senders.push_back(link::make_link(*p));
          robot_block =
              std::min(robot_block, static_cast<std::size_t>(trials.back()->robot().receiver_block_samples()));
          ear_block = std::min(ear_block, static_cast<std::size_t>(senders.back()->answer_block_samples()));
          names += (names.empty() ? "" : "+") + p->name;
        }
        std::vector<float> noise(static_cast<std::size_t>(audio_s * rate_hz), 0.0f);
        add_noise(noise, kNoiseOnlyDbfs, rate_hz, 1);
        const Signal frames = frames_in_turn(trials, audio_s, rate_hz);
        const Signal answers = answers_in_turn(trials, audio_s, rate_hz);
        const Signal quiet{noise, std::vector<std::size_t>(trials.size(), 0)};

        nlohmann::json doc{{"benchmark", "receive"}, {"profiles", names}, {"signals", nlohmann::json::array()}};
        int status = 0;
        const auto report = [&](const char* path, const char* signal, const Measurement& m, const Signal& s) {
          const double speed = m.audio_s / m.cpu_s;
          std::string heard;
          nlohmann::json per_profile = nlohmann::json::object();
          for (std::size_t p = 0; p < trials.size(); ++p) {
            const std::string& name = trials[p]->profile().name;
            heard += (heard.empty() ? "" : ", ") + name + " " + std::to_string(m.heard[p]) + " of " +
                     std::to_string(s.expected[p]);
            per_profile[name] = {{"expected", s.expected[p]}, {"heard", m.heard[p]}};
            if (m.heard[p] < s.expected[p]) {
              std::fprintf(stderr, "dtmf-bench-receive: %s %s: %s heard %zu of its %zu\n", path, signal, name.c_str(),
                           m.heard[p], s.expected[p]);
              status = 1;
            }
          }
          std::printf("receive path  %-5s %-7s %-9s %6.1f s of audio in %6.3f s CPU: %8.0f x real time (%s)\n", path,
                      signal, names.c_str(), m.audio_s, m.cpu_s, speed, heard.c_str());
          doc["signals"].push_back({{"path", path},
                                    {"signal", signal},
                                    {"audio_s", m.audio_s},
                                    {"cpu_s", m.cpu_s},
                                    {"realtime_factor", speed},
                                    {"per_profile", per_profile}});
        };
        report("robot", "noise", robot_path(trials, noise, robot_block, rate_hz), quiet);
        report("robot", "frames", robot_path(trials, frames.audio, robot_block, rate_hz), frames);
        report("ear", "noise", answer_ear(senders, noise, ear_block, rate_hz), quiet);
        report("ear", "answers", answer_ear(senders, answers.audio, ear_block, rate_hz), answers);
        write_json(json_path, doc);
        return status;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-receive: %s\n", why.c_str()); });
}
