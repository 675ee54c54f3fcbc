// dtmf-bench-roundtrip: the link's round trip in a simulated room — command to confirmation.
//
// The sender's own core (server/core/sender_core.h: its queue, listen before talk, retries,
// answer matching, exactly what dtmf-server runs) and a robot face each other `d` metres apart
// in a simulated room (sim::AcousticChannel both ways: delay, spreading, air absorption, RT60
// 0.3 s, pink noise at -50 dBFS; each microphone also hears its own loudspeaker from 0.1 m, as
// in the e2e air), or with --rir in a measured room both ways (room_model.h: near a loudspeaker
// only its direct sound grows). Both run block by block (--block-samples, 5 ms by default, like
// low-latency sound cards) in simulated time: the robot answers every verdict with ACK / NACK
// at its next block; the core is asked what to play at each block's start, and again when a
// command is handed over, and hears each block the sender's microphone took, as the live
// transmitter drives it. The next command is handed over the moment one ends. Per command: the
// time from being handed over (as an RPC would hand it) to its confirmation. Throughput:
// payload bits of the confirmed commands (frame_trials.h: command_payload_bits) over the run's
// audio time. No server, no gRPC: the link's own share of a command's latency, which
// dtmf-bench-e2e measures through the whole system.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/authenticated_flag.h"
#include "common/bench_report.h"
#include "frames/frame_trials.h"
#include "frames/queued_speaker.h"
#include "profile/link_profile.h"
#include "program_main.h"
#include "reliability/carrier_sense.h"
#include "sender_core.h"
#include "signal/hop_reply.h"
#include "sim/acoustic_channel.h"
#include "sim/room_model.h"

using namespace dtmf;
using namespace dtmf::bench;

namespace {

struct Options {
  bool authenticated = false;
  int commands = 200;
  double distance_m = 1;
  std::string rir;  // a measured room both ways instead of the simulated one
  std::size_t block_samples = 240;
  std::uint64_t seed = 1;
  double own_speaker_m = 0.1;        // 0: the sender's microphone does not hear its own loudspeaker
  double own_speaker_db = 0;         // the sender's own loudspeaker heard this much louder (a margin)
  double robot_own_speaker_m = 0.1;  // 0: the robot's microphone does not hear its own loudspeaker
  bool trace = false;
  double answer_delay_ms = 0;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(
      std::min<double>(static_cast<double>(v.size()) - 1, p * static_cast<double>(v.size())))];
}

nlohmann::json run(const LinkProfile& profile, const Options& o) {
  sim::ChannelConfig room;
  room.noise = sim::parse_noise("pink", -50);
  std::shared_ptr<const sim::RoomModel> measured;
  if (o.rir.empty()) {
    room.reverb.rt60_s = 0.3;
  } else {
    room.room.rir_file = o.rir;
    measured = std::make_shared<const sim::RoomModel>(room.room, profile.sample_rate_hz);
  }
  const auto channel = [&](std::uint64_t seed) {
    room.seed = seed;
    return measured ? std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, room, measured)
                    : std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, room);
  };
  const auto to_robot_channel = channel(o.seed), to_sender_channel = channel(o.seed + 1);
  sim::AcousticChannel& to_robot = *to_robot_channel;
  sim::AcousticChannel& to_sender = *to_sender_channel;
  to_robot.add_transmitter(o.distance_m);
  if (o.robot_own_speaker_m > 0) to_robot.add_transmitter(o.robot_own_speaker_m, false);
  if (o.own_speaker_m > 0) to_sender.add_transmitter(o.own_speaker_m, false);
  to_sender.add_transmitter(o.distance_m);

  link::LinkOptions keyed;  // each side its own counters, in memory
  keyed.key = bench_key(o.authenticated);
  // Numbered from 0, so that a run is the same run every time: a sender left to draw its first
  // sequence number at random sends other frames, answered in other lanes, in every process.
  keyed.first_sequence = 0;
  std::vector<server::RobotLinks> robots(1);
  robots.front().links = link::make_links(keyed);
  server::TransmitterOptions options;
  options.backoff_seed = o.seed;
  options.allow_unauthenticated = true;  // the profile asked for, keyed or not
  server::SenderCore sender(std::move(robots), profile, options, {});
  const link::Link& link = sender.link_of(profile);
  const auto robot_link = link::make_link(profile, keyed);
  Responder robot(*robot_link);
  server::ReplyListeners sender_ears(sender.every_link());
  Speaker sender_speaker, robot_speaker;
  const double ms_per_sample = 1000.0 / profile.sample_rate_hz;
  const std::vector<command::Command> commands = {command::DriveForDuration{50, 2}, command::TurnForDuration{-30, 1.5},
                                                  command::DriveForward{80}, command::Stop{}};

  std::vector<double> latencies_ms;
  long frames_sent = 0, frames_first_time = 0, retransmissions = 0, failed_commands = 0, payload_bits = 0;
  int command_index = -1;
  double handed_over_ms = 0, frame_started_ms = 0;
  std::shared_ptr<server::Job> job;
  auto next_command = [&](double now_ms) {
    if (++command_index >= o.commands) return;
    job = server::taken(sender.submit(commands[static_cast<std::size_t>(command_index) % commands.size()],
                                      server::Policy::Fail, std::chrono::milliseconds(0), false, nullptr, 0, now_ms));
    handed_over_ms = now_ms;
  };
  // The core's events: what each frame and command came to.
  auto take_events = [&](double now_ms) {
    using Kind = server::ProgressEvent::Kind;
    for (const auto& [of, event] : sender.take_events()) {
      if (event.kind == Kind::Retransmitting) ++retransmissions;
      if (event.kind == Kind::Ack && event.attempt == 1) ++frames_first_time;
      if (of != job || event.outcome == server::Outcome::Pending) continue;
      if (event.outcome == server::Outcome::Confirmed) {
        latencies_ms.push_back(event.at_ms - handed_over_ms);
        payload_bits += link.payload_bits(of->command());
      } else {
        ++failed_commands;
      }
      next_command(now_ms);
    }
  };

  // With --trace, every reading of the reply bands with half its tones heard (hopped profiles).
  std::optional<signal::HopReplyListener> trace_ear;
  if (o.trace && profile.hops().reply_hop_samples > 0) trace_ear.emplace(profile, 6);
  std::vector<float> speaker_block(o.block_samples), robot_block(o.block_samples), own_block(o.block_samples), heard;
  const auto own_gain = static_cast<float>(std::pow(10.0, o.own_speaker_db / 20));
  // As a server that starts: the sender hears its room for a second before its first command,
  // else the first sound it hears would be its floor (reliability/carrier_sense.h). Not counted.
  constexpr double kWarmUpMs = 1000;
  long long samples = 0, warm_up_samples = 0;
  while (command_index < o.commands) {
    const double now_ms = static_cast<double>(samples) * ms_per_sample;  // start of this block
    if (command_index < 0 && now_ms >= kWarmUpMs) {
      warm_up_samples = samples;
      next_command(now_ms);
    }
    // What the loudspeaker plays from this block on: the core's frames, as it names them. A
    // command confirmed now hands the next one over now, and the core is asked again, as the
    // live transmitter's submit wakes its loudspeaker: the next frame may start in this block.
    for (int handed = command_index;; handed = command_index) {
      for (auto step = sender.next(now_ms); std::holds_alternative<server::SenderCore::Play>(step);
           step = sender.next(now_ms)) {
        const auto& play = std::get<server::SenderCore::Play>(step);
        sender_speaker.queue(play.frame->audio);
        ++frames_sent;
        frame_started_ms = now_ms;
        if (o.trace)
          std::printf("frame at %.1f ms, %s, %zu samples, lane %d\n", now_ms, play.job->description().c_str(),
                      play.frame->audio.size(), play.frame->answer_lane);
      }
      take_events(now_ms);
      if (command_index == handed || command_index >= o.commands) break;
    }
    sender_speaker.next_block(speaker_block);
    robot_speaker.next_block(robot_block);
    samples += static_cast<long long>(o.block_samples);
    const double end_ms = static_cast<double>(samples) * ms_per_sample;

    heard.clear();
    if (o.robot_own_speaker_m > 0) {
      const std::array<std::span<const float>, 2> both{std::span<const float>(speaker_block),
                                                       std::span<const float>(robot_block)};
      to_robot.process(both, heard);
    } else {
      to_robot.process(speaker_block, heard);
    }
    for (auto& answer : robot.feed(heard)) {
      if (o.trace) std::printf("  %9.1f robot answers (%zu samples)\n", end_ms - frame_started_ms, answer.size());
      if (o.answer_delay_ms > 0)
        answer.insert(answer.begin(), static_cast<std::size_t>(o.answer_delay_ms / ms_per_sample), 0.0f);
      robot_speaker.queue(std::move(answer));
    }

    heard.clear();
    if (o.own_speaker_m > 0) {
      std::transform(speaker_block.begin(), speaker_block.end(), own_block.begin(),
                     [&](float s) { return s * own_gain; });
      const std::array<std::span<const float>, 2> both{std::span<const float>(own_block),
                                                       std::span<const float>(robot_block)};
      to_sender.process(both, heard);
    } else {
      to_sender.process(std::span<const float>(robot_block), heard);
    }
    if (trace_ear) {
      for (const auto& r : trace_ear->feed(heard)) {
        std::printf("  %9.1f reading lane %d, heard %2d:", r.heard_ms - frame_started_ms, r.lane, r.heard);
        for (int t : r.tones) std::printf(" %2d", t);
        std::printf("\n");
      }
    }
    // The sender's microphone, as the live transmitter hands it over: the block's level, then
    // each answer its ears read (their times are this air's, from its first sample).
    sender.hear_level(reliability::block_level_dbfs(heard), end_ms);
    for (const server::HeardAnswer& a : sender_ears.feed(heard)) {
      if (o.trace)
        std::printf("  %9.1f %s heard%s\n", a.answer.heard_ms - frame_started_ms, a.answer.ack ? "ACK" : "NACK",
                    a.answer.tag_reading ? " (tag chord)" : "");
      sender.hear_answer(a, a.answer.heard_ms);
    }
    take_events(end_ms);
  }
  const double run_s = static_cast<double>(samples - warm_up_samples) / profile.sample_rate_hz;
  const double median = percentile(latencies_ms, 0.5), p95 = percentile(latencies_ms, 0.95);
  const double max = latencies_ms.empty() ? 0 : *std::max_element(latencies_ms.begin(), latencies_ms.end());
  std::printf(
      "round trip  %-5s %d commands at %.1f m: confirmed %zu, failed %ld; latency median %.1f ms, p95 %.1f, max %.1f; "
      "%.1f bit/s net; %ld of %ld frames answered at the first attempt, %ld retransmissions\n",
      profile.name.c_str(), o.commands, o.distance_m, latencies_ms.size(), failed_commands, median, p95, max,
      static_cast<double>(payload_bits) / run_s, frames_first_time, frames_sent, retransmissions);
  return {{"benchmark", "roundtrip"},
          {"profile", profile.name},
          {"authenticated", o.authenticated},
          {"commands", o.commands},
          {"distance_m", o.distance_m},
          {"room", o.rir.empty() ? "simulated, RT60 0.3 s" : o.rir},
          {"block_samples", o.block_samples},
          {"confirmed", latencies_ms.size()},
          {"failed", failed_commands},
          {"latency_ms", {{"median", median}, {"p95", p95}, {"max", max}}},
          {"latencies_ms", latencies_ms},
          {"payload_bits", payload_bits},
          {"run_s", run_s},
          {"throughput_bps", static_cast<double>(payload_bits) / run_s},
          {"frames_sent", frames_sent},
          {"frames_first_time", frames_first_time},
          {"retransmissions", retransmissions}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dtmf-bench-roundtrip: command to confirmation over the simulated room, block by block");
  std::string profile_name = "seed", json_path;
  Options o;
  app.add_option("--profile", profile_name, "link profile: " + profile_names())->capture_default_str();
  add_authenticated_flag(app, o.authenticated);
  app.add_option("--json", json_path, "write the results to this JSON file");
  app.add_option("--commands", o.commands, "commands to send, one after another")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--distance-m", o.distance_m, "sender to robot")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--rir", o.rir, "a measured room's impulse response (WAV), both ways, instead of the simulated room")
      ->check(CLI::ExistingFile);
  app.add_option("--block-samples", o.block_samples, "audio block of both sides")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--own-speaker-m", o.own_speaker_m,
                 "the sender's own loudspeaker's distance from its microphone (0: unheard)")
      ->capture_default_str();
  app.add_option("--own-speaker-db", o.own_speaker_db,
                 "the sender's own loudspeaker heard this much louder than the 0.1 m model (a margin: a louder "
                 "loudspeaker, a nearer microphone)")
      ->capture_default_str();
  app.add_option("--robot-own-speaker-m", o.robot_own_speaker_m,
                 "the robot's own loudspeaker's distance from its microphone (0: unheard)")
      ->capture_default_str();
  app.add_option("--answer-delay-ms", o.answer_delay_ms, "the robot waits this long before it answers");
  app.add_flag("--trace", o.trace, "print every transmission, the robot's answers and the reply readings");
  app.add_option("--seed", o.seed, "random seed (noise)")->capture_default_str();
  if (const auto exit_code = program::parse(app, argc, argv)) return *exit_code;
  return program::run(
      [&] {
        write_json(json_path, run(profile_by_name(profile_name), o));
        return 0;
      },
      [](const std::string& why) { std::fprintf(stderr, "dtmf-bench-roundtrip: %s\n", why.c_str()); });
}
