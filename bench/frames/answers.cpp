// dtmf-bench-answers: the answer path — the robot's ACKs through a room to the sender's
// ear, one row per case, the answer-path table of docs/benchmarks.md.
//
// Each answer is the robot's ACK to a frame the sender waits for (random commands planned
// one after another as a sender plans them, so numbered consecutively; with a key tagged for
// each frame), in its own slot of `--slot-ms`: by default the round trip's cadence, a frame
// and its answer, so that each answer meets the last one's reverberant tail as in a
// sender's stream of commands (answers 400 ms apart lost none in the smoking room while the
// round trip lost 44 %: docs/protocol.md, "Answers in reverberant rooms"); the sender's ear
// hears the whole stream and each answer counts as heard when the ear gives an answer that
// answers its frame (link/answer_wait.h) within its slot. Cases: the measured rooms and
// image-source rooms, each alone and with the sender's own loudspeaker 0.1 m from its microphone
// through the same room (as the round trip's and the test air's: sim/room_model.h): unkeyed, one of its frames sounding
// across every answer (from a chord before the answer begins to a chord after it ends: an
// unkeyed answer sounds below the frames); keyed, the frame answered itself, ending 0-20 ms
// before its answer begins, as a sender that waits for each answer sends it (a tagged ACK
// sounds in the frame bands: reliability/tag_chord.h). Pink noise at -50 dBFS. Also counted: an answer taken for a
// slot's frame before the robot's answer to it began (wrong: an echo of an earlier answer, or noise), and slots
// answered more than once (the same answer read again: harmless, the sender stops waiting at the first).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <random>

#include "command/random_command.h"
#include "command/word_codec.h"
#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/channel_case.h"
#include "link/answer_wait.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "sim/acoustic_channel.h"
#include "sim/channel_flags.h"
#include "sim/room_model.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

constexpr const char* kQuiet = " --noise pink --noise-dbfs -50";
constexpr double kOwnSpeakerM = 0.1;  // the sender's own loudspeaker from its microphone
constexpr double kLeadInS = 2;        // the ear hears the room before the first answer

struct AnswerCase {
  ChannelCase channel;
  bool own_frames = false;
};

struct Counts {
  std::uint64_t answers = 0, heard = 0, wrong = 0, twice = 0;
  int most_stray = 0;  // tag chord readings in a slot that answered nothing
  void add(const Counts& o) {
    answers += o.answers;
    heard += o.heard;
    wrong += o.wrong;
    twice += o.twice;
    most_stray = std::max(most_stray, o.most_stray);
  }
};

std::vector<AnswerCase> default_cases(const std::string& rirs) {
  std::vector<ChannelCase> rooms;
  for (const char* room : kMeasuredRooms) {
    for (const char* d : {"1", "3"}) {
      rooms.push_back(
          {std::string(room) + " " + d + " m", "--rir " + rirs + "/" + room + ".wav --distance " + d + kQuiet});
    }
  }
  for (const char* rt60 : {"0.6", "1.0"}) {
    rooms.push_back({std::string("image-source RT60 ") + rt60 + " s 3 m",
                     std::string("--room 6x8x3 --room-rt60 ") + rt60 + " --distance 3" + kQuiet});
  }
  std::vector<AnswerCase> cases;
  for (const ChannelCase& room : rooms) {
    cases.push_back({room, false});
    cases.push_back({{room.name + ", own loudspeaker 0.1 m", room.flags}, true});
  }
  return cases;
}

// One stream of `answers` slots through the case's room.
Counts run_stream(const LinkProfile& profile, const AnswerCase& c, const sim::ChannelSetup& setup,
                  const std::shared_ptr<const sim::RoomModel>& room, const link::LinkOptions& options,
                  std::size_t answers, double slot_ms, bool every_second, std::uint64_t seed) {
  const auto sender = link::make_link(profile, options);
  const auto robot = link::make_link(profile, options);
  const auto own = link::make_link(profile, options);  // the frames the sender sends meanwhile
  const double samples_per_ms = profile.sample_rate_hz / 1000.0;
  const auto slot = static_cast<std::size_t>(slot_ms * samples_per_ms);
  const auto lead = static_cast<std::size_t>(kLeadInS * 1000 * samples_per_ms);
  std::vector<float> answer_track(lead + answers * slot + slot, 0.0f), own_track(answer_track.size(), 0.0f);
  std::vector<link::TransmitFrame> frames;
  std::vector<double> answer_start_ms;
  std::mt19937_64 rng(seed);
  // A random command the profile can carry: the seed's 12-bit words carry no Velocity (plan()
  // throws for it), and a sender sends only what its profile carries.
  const auto next_command = [&] {
    for (;;) {
      command::Command command = command::random_command(rng);
      try {
        sender->frame_count(command);
        return command;
      } catch (const command::ParameterError&) {
      }
    }
  };
  // Planned and confirmed as a sender does, so numbered one after another (a keyed sender's
  // first plan adds a synchronisation frame, confirmed too).
  const auto next_frame = [&] {
    const auto planned = sender->plan(next_command());
    for (const auto& f : planned) sender->confirmed(f);
    return planned.back();
  };
  for (std::size_t k = 0; k < answers; ++k) {
    frames.push_back(next_frame());
    if (every_second) frames.back() = next_frame();
    const link::TransmitFrame& f = frames.back();
    const std::vector<float> answer = robot->answer_audio(link::intact_reception(f));
    const std::size_t at = lead + k * slot + slot / 8;
    answer_start_ms.push_back(static_cast<double>(at) / samples_per_ms);
    // A slot need not hold all of a long frame of the sender's (the seed's: 0.8 s): the tracks
    // grow to what is written.
    const auto fit = [&](std::size_t end) {
      if (end > answer_track.size()) {
        answer_track.resize(end, 0.0f);
        own_track.resize(end, 0.0f);
      }
    };
    fit(at + answer.size());
    std::copy(answer.begin(), answer.end(), answer_track.begin() + static_cast<long>(at));
    if (c.own_frames) {
      const std::vector<float> frame = f.authenticated ? f.audio : own->random_frame(rng()).audio;
      const std::size_t chord = frame.size() / 3;
      // Unkeyed, its start anywhere from a whole frame before the answer's to the answer's
      // end, so that the two overlap by at least a third of the frame; keyed, the frame
      // answered, as the robot times its answer (which begins tag_after_frame_ms after where
      // it placed the frame's end): the sound's way there and back, the robot's placing of
      // the frame from that much early to tag_late_ms late.
      std::uniform_int_distribution<std::size_t> offset(0, frame.size() + answer.size() - 2 * chord);
      const HopPlan* hops = std::get_if<HopPlan>(&profile.plan);
      std::uniform_real_distribution<double> placed_ms(hops ? -hops->tag_after_frame_ms : 0.0,
                                                       hops ? hops->tag_late_ms : 0.0);
      const double flight_ms = 2000.0 * setup.distance_m / sim::kSpeedOfSoundMps;
      const auto gap = static_cast<std::size_t>(std::lround((flight_ms + placed_ms(rng)) * samples_per_ms));
      const std::size_t start = f.authenticated ? at - frame.size() - gap : at + chord + offset(rng) - frame.size();
      fit(start + frame.size());
      for (std::size_t i = 0; i < frame.size(); ++i) own_track[start + i] += frame[i];
    }
  }
  sim::ChannelConfig config = setup.config;
  config.seed = seed;
  const auto channel = room ? std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config, room)
                            : std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config);
  channel->add_transmitter(setup.distance_m);
  channel->add_transmitter(kOwnSpeakerM, false);
  const std::array<std::span<const float>, 2> both{std::span<const float>(answer_track),
                                                   std::span<const float>(own_track)};
  std::vector<float> heard;
  channel->process(both, heard);

  std::vector<link::AnswerWait> waits;
  for (const auto& f : frames) waits.emplace_back(*sender, f);
  std::vector<int> right(answers, 0), wrong(answers, 0), stray(answers, 0);
  const auto ear = sender->answer_listener();
  const auto block = static_cast<std::size_t>(sender->answer_block_samples());
  for (std::size_t at = 0; at < heard.size(); at += block) {
    for (const link::Answer& a :
         ear->feed(std::span<const float>(heard).subspan(at, std::min(block, heard.size() - at)))) {
      const double slot_at = (a.heard_ms * samples_per_ms - static_cast<double>(lead)) / static_cast<double>(slot);
      if (slot_at < 0 || slot_at >= static_cast<double>(answers)) continue;
      const auto k = static_cast<std::size_t>(slot_at);
      if (!waits[k].answered_by(a)) {
        stray[k] += a.tag_reading ? 1 : 0;
        continue;
      }
      // Taken before the robot's answer had begun: an echo of an earlier answer, or noise.
      ++(a.heard_ms < answer_start_ms[k] ? wrong[k] : right[k]);
    }
  }
  Counts n;
  for (std::size_t k = 0; k < answers; ++k) {
    ++n.answers;
    n.heard += right[k] >= 1 ? 1 : 0;
    n.twice += right[k] >= 2 ? 1 : 0;
    n.wrong += wrong[k] >= 1 ? 1 : 0;
    n.most_stray = std::max(n.most_stray, stray[k]);
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-answers: the robot's answers heard by the sender through rooms, beside its own frames");
  std::string profile_name = "fast", json_path, rirs = "bench/rirs";
  std::vector<std::string> case_texts;
  std::size_t answers_per_case = 1000, chunk = 100;
  double slot_ms = 0;
  std::uint64_t seed = 1;
  unsigned threads = default_threads();
  bool authenticated = false, own_frames = false, every_second = false;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  add_authenticated_flag(app, authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--case", case_texts, "NAME=FLAGS (dtmfctl simulate's channel flags); repeatable; default: the table");
  app.add_flag("--own-frames", own_frames,
               "with --case: the sender's own frames from its loudspeaker 0.1 m from its microphone");
  app.add_option("--rirs", rirs, "where the measured rooms are")->capture_default_str();
  app.add_option("--answers", answers_per_case, "answers per case")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--chunk", chunk, "answers per stream")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--slot-ms", slot_ms,
                 "each answer's slot (default: the round trip's cadence, a frame and its answer, at least 200 ms, "
                 "or an answer and the ear's lockout if longer: seed 1200 ms)")
      ->check(CLI::Range(200.0, 2000.0));
  app.add_flag("--every-second-frame", every_second,
               "answer only every second frame a sender plans: (fast) every answer in one reply lane, as before "
               "the lanes");
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  app.add_option("--threads", threads, "worker threads")->capture_default_str()->check(CLI::PositiveNumber);
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        const LinkProfile& profile = profile_by_name(profile_name);
        // Answers closer than the ear's lockout would be heard as one (the seed's reply ear
        // locks 900 ms after a pass): such a slot measures the lockout, not the room.
        link::LinkOptions options;
        options.key = bench_key(authenticated);
        options.first_sequence = 0;
        if (slot_ms == 0) {
          const double frame_ms = link::make_link(profile, options)->random_frame(seed).tone_ms;
          const auto* words = std::get_if<WordPlan>(&profile.plan);
          const double lockout_ms = words ? words->debounce.lockout_ms : 0;  // the hopped ear has none
          slot_ms = std::max({200.0, frame_ms + profile.timing.ack_ms, profile.timing.ack_ms + lockout_ms});
        }
        std::vector<AnswerCase> cases;
        for (const auto& t : case_texts) cases.push_back({parse_channel_case(t), own_frames});
        if (cases.empty()) cases = default_cases(rirs);
        std::printf("dtmf-bench-answers: profile %s%s%s, seed %llu, %zu answers per case, %.0f ms slots, %u threads\n",
                    profile.name.c_str(), authenticated ? " (authenticated)" : "",
                    every_second ? ", every second frame answered" : "", static_cast<unsigned long long>(seed),
                    answers_per_case, slot_ms, threads);
        std::printf("%-48s %7s %9s %6s %6s %8s\n", "case", "answers", "heard", "wrong", "twice", "stray");
        std::fflush(stdout);
        const auto started = std::chrono::steady_clock::now();
        nlohmann::json rows = nlohmann::json::array();
        for (std::size_t ci = 0; ci < cases.size(); ++ci) {
          const AnswerCase& c = cases[ci];
          const sim::ChannelSetup setup = channel_setup_of(c.channel);
          const auto room = setup.config.room.enabled()
                                ? std::make_shared<const sim::RoomModel>(setup.config.room, profile.sample_rate_hz)
                                : nullptr;
          Counts total;
          std::size_t next = 0;
          while (next < answers_per_case) {
            std::vector<std::future<Counts>> running;
            for (unsigned t = 0; t < threads && next < answers_per_case; ++t) {
              const std::size_t n = std::min(chunk, answers_per_case - next);
              const std::uint64_t stream_seed = seed * 1000003 + ci * 10007 + next;
              running.push_back(std::async(std::launch::async, [&, n, stream_seed] {
                return run_stream(profile, c, setup, room, options, n, slot_ms, every_second, stream_seed);
              }));
              next += n;
            }
            for (auto& r : running) total.add(r.get());
          }
          const double rate = static_cast<double>(total.heard) / static_cast<double>(total.answers);
          std::printf("%-48s %7llu %8.2f%% %6llu %6llu %8d\n", c.channel.name.c_str(),
                      static_cast<unsigned long long>(total.answers), 100 * rate,
                      static_cast<unsigned long long>(total.wrong), static_cast<unsigned long long>(total.twice),
                      total.most_stray);
          std::fflush(stdout);
          rows.push_back({{"case", c.channel.name},
                          {"flags", c.channel.flags},
                          {"own_frames", c.own_frames},
                          {"answers", total.answers},
                          {"heard", total.heard},
                          {"heard_rate", rate},
                          {"wrong", total.wrong},
                          {"twice", total.twice},
                          {"most_stray", total.most_stray}});
        }
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
        std::printf("%.1f s\n", took.count());
        write_json(json_path, {{"benchmark", "answers"},
                               {"profile", profile.name},
                               {"authenticated", authenticated},
                               {"seed", seed},
                               {"answers_per_case", answers_per_case},
                               {"slot_ms", slot_ms},
                               {"every_second_frame", every_second},
                               {"frame_ms", link::make_link(profile, options)->random_frame(seed).tone_ms},
                               {"wall_s", took.count()},
                               {"cases", rows}});
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-answers: %s\n", why.c_str()); });
}
