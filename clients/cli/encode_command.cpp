// dtmfctl encode: a command (or a raw word) through the sender's path, printed and optionally
// rendered to a WAV with the profile's timing.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "command/test_sequence.h"
#include "command/command_payload.h"
#include "command/word_codec.h"
#include "frame_output.h"
#include "link/sender_path.h"
#include "link/transmit_plan.h"
#include "reliability/crc4.h"
#include "offline_commands.h"
#include "physical/wav_file.h"

namespace dtmf::cli {

namespace {

struct EncodeOptions {
  bool json = false;
  std::string wav;
  std::string profile = "seed";
  std::optional<int> word;
  std::optional<double> speed;
  std::optional<double> rotation;
  std::optional<double> duration;
  std::string kind;  // drive, turn, stop, reset, sequence
};

command::Command build_command(const EncodeOptions& o) {
  if (o.kind == "drive") {
    if (o.duration) return command::DriveForDuration{*o.speed, *o.duration};
    return command::DriveForward{*o.speed};
  }
  if (o.kind == "turn") {
    if (o.duration) return command::TurnForDuration{*o.rotation, *o.duration};
    return command::Turn{*o.rotation};
  }
  if (o.kind == "stop") return command::Stop{};
  return command::Reset{};
}

// The fast profile: one frame per command, numbered from 0, each followed by the time its
// answer takes (kAnswerWaitMs), as a sender would space them.
constexpr double kAnswerWaitMs = 100;

int run_encode_command_frames(const EncodeOptions& o, const LinkProfile& profile) {
  if (o.word) throw std::invalid_argument("--word: the " + profile.name + " profile sends whole commands, not words; "
                                          "give a command (drive, turn, stop, reset, sequence)");
  const std::vector<command::Command> commands =
      o.kind == "sequence" ? command::seed_test_sequence() : std::vector<command::Command>{build_command(o)};
  std::uint8_t sequence = 0;
  std::vector<float> audio;
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const link::TransmitFrame f = link::plan_transmission(profile, commands[i], sequence).front();
    const double t_ms = 1000.0 * static_cast<double>(audio.size()) / profile.sample_rate_hz;
    const std::string bits = reliability::bit_string(f.bits, f.bit_count);
    const std::string what = command::describe(command::quantised_payload(commands[i]));
    if (o.json) {
      nlohmann::json json{{"index", i}, {"sequence", *f.sequence}, {"frame", bits}, {"tones_hz", f.tones_hz},
                          {"command", what}};
      if (!o.wav.empty()) json["t_ms"] = t_ms;
      std::cout << json.dump() << '\n';
    } else {
      std::printf("frame %zu/%zu  seq %2u  %s  %s\n", i + 1, commands.size(), static_cast<unsigned>(*f.sequence),
                  bits.c_str(), what.c_str());
    }
    audio.insert(audio.end(), f.audio.begin(), f.audio.end());
    audio.resize(audio.size() + static_cast<std::size_t>(profile.samples_for_ms(kAnswerWaitMs)), 0.0f);
  }
  if (!o.json) std::cout << "encodes: " << commands.size() << " command" << (commands.size() == 1 ? "" : "s")
                         << ", one 48-bit frame each (profile " << profile.name << ")\n";
  if (!o.wav.empty()) {
    physical::write_wav_file(o.wav, audio, profile.sample_rate_hz);
    if (!o.json) std::printf("wrote %s: %.2f s at %d Hz\n", o.wav.c_str(),
                             static_cast<double>(audio.size()) / profile.sample_rate_hz, profile.sample_rate_hz);
  }
  return 0;
}

int run_encode(const EncodeOptions& o) {
  const LinkProfile& profile = profile_by_name(o.profile);
  if (profile.frame_format == FrameFormat::Command48) return run_encode_command_frames(o, profile);
  std::vector<link::PlannedFrame> frames;
  std::string what;
  if (o.word) {
    frames.push_back(link::plan_word(profile, static_cast<command::Word>(*o.word)));
    what = "word " + std::to_string(*o.word);
  } else if (o.kind == "sequence") {
    const auto commands = command::seed_test_sequence();
    for (const auto& c : commands) {
      const auto planned = link::plan_command(profile, c);
      frames.insert(frames.end(), planned.begin(), planned.end());
    }
    what = "the seed's test sequence, " + std::to_string(commands.size()) + " commands";
  } else {
    const command::Command command = build_command(o);
    frames = link::plan_command(profile, command);
    what = command::describe(command::quantised(command));
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (o.json) {
      nlohmann::json json = frame_json(frames[i]);
      json["index"] = i;
      if (!o.wav.empty()) json["t_ms"] = link::frame_start_ms(profile, i);
      std::cout << json.dump() << '\n';
    } else {
      std::cout << "frame " << i + 1 << '/' << frames.size() << "  " << frame_line(frames[i]) << '\n';
    }
  }
  if (!o.json) std::cout << "encodes: " << what << " (profile " << profile.name << ")\n";
  if (!o.wav.empty()) {
    const std::vector<float> audio = link::render_frames(profile, frames);
    physical::write_wav_file(o.wav, audio, profile.sample_rate_hz);
    if (!o.json) {
      std::printf("wrote %s: %.2f s at %d Hz\n", o.wav.c_str(),
                  static_cast<double>(audio.size()) / profile.sample_rate_hz, profile.sample_rate_hz);
    }
  }
  return 0;
}

}  // namespace

void add_encode_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<EncodeOptions>();
  CLI::App* encode = app.add_subcommand(
      "encode", "Print the frames of a command (word, frame bits, CRC, tones); --wav renders them");
  encode->add_option("--wav", o->wav, "also write the chords to this WAV file (profile timing; fast: each frame then 100 ms for its answer)");
  encode->add_option("--profile", o->profile, "link profile: " + profile_names())->capture_default_str();
  encode->add_option("--word", o->word, "encode one raw 12-bit word instead of a command")
      ->check(CLI::Range(0, 4095));

  CLI::App* drive = encode->add_subcommand("drive", "drive forward: DRIVE_FOR_DURATION, or DRIVE_FORWARD without --duration");
  drive->add_option("--speed", o->speed, "speed, percent of the robot's maximum (0..100)")->required();
  drive->add_option("--duration", o->duration, "seconds (0..8); omit to drive until the next command");
  CLI::App* turn = encode->add_subcommand("turn", "turn on the spot: TURN_FOR_DURATION, or TURN without --duration");
  turn->add_option("--rotation", o->rotation, "rotation, percent of the maximum; positive turns left (-100..100)")->required();
  turn->add_option("--duration", o->duration, "seconds (0..8); omit to turn until the next command");
  CLI::App* stop = encode->add_subcommand("stop", "stop the robot (RESET, STOP)");
  CLI::App* reset = encode->add_subcommand("reset", "return the robot to MODE_SELECT (RESET)");
  CLI::App* sequence = encode->add_subcommand("sequence", "the seed's 65-frame system test sequence (its section 10)");
  encode->require_subcommand(0, 1);
  encode->callback([o, encode, &global, &run] {
    const auto chosen = encode->get_subcommands();
    if (!chosen.empty()) o->kind = chosen.front()->get_name();
    if (chosen.empty() == !o->word.has_value()) {
      throw CLI::ValidationError("encode", "give either a command (drive, turn, stop, reset, sequence) or --word N");
    }
    run = [o, &global] {
      o->json = global.json;  // one JSON object per frame: word, frame, crc, tones_hz, index
      return run_encode(*o);
    };
  });
}

}  // namespace dtmf::cli
