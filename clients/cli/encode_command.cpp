// dtmfctl encode: a command (or a raw word) through the sender's path, printed and optionally
// rendered to a WAV with the profile's timing.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "command/robot_model.h"
#include "command/test_sequence.h"
#include "frame_output.h"
#include "key_flags.h"
#include "link/link.h"
#include "offline_commands.h"
#include "physical/wav_file.h"

namespace dtmf::cli {

namespace {

struct EncodeOptions {
  bool json = false;
  std::string wav;
  std::string profile;  // empty: fast with a key, else seed (link::default_profile)
  std::optional<int> word;
  std::optional<double> speed;
  std::optional<double> rotation;
  std::optional<double> duration;
  std::optional<double> linear_mps;
  std::optional<double> angular_radps;
  double lease_s = 1.0;
  std::string robot = "burger";
  std::string kind;  // drive, turn, stop, reset, sequence, velocity
  program::KeyFlags keys;
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
  if (o.kind == "velocity") {
    return command::velocity_command(command::robot_model_by_name(o.robot), o.linear_mps.value_or(0),
                                     o.angular_radps.value_or(0), o.lease_s);
  }
  if (o.kind == "stop") return command::Stop{};
  return command::Reset{};
}

int run_encode(const EncodeOptions& o) {
  link::LinkOptions options = program::link_options(o.keys);
  options.first_sequence = 0;  // unauthenticated frames are numbered from 0, where the format numbers them
  const auto made = link::make_link(
      o.profile.empty() ? link::default_profile(link::make_links(options)) : profile_by_name(o.profile), options);
  link::Link& link = *made;
  if (link.keyed() && !link.can_authenticate()) {
    throw std::invalid_argument("--key: the " + link.name() +
                                " profile's frames cannot carry a MAC; use --profile fast");
  }
  std::vector<link::TransmitFrame> frames;
  std::vector<std::string> commands_of;  // what each frame's command does, as the robot will execute it
  std::string what;
  if (o.word) {
    const auto frame = link.plan_payload_word(static_cast<std::uint32_t>(*o.word));
    if (!frame) {
      throw std::invalid_argument("--word: the " + link.name() +
                                  " profile sends whole commands, not words; "
                                  "give a command (drive, turn, stop, reset, sequence)");
    }
    frames.push_back(*frame);
    commands_of.emplace_back();
    what = "word " + std::to_string(*o.word);
  } else {
    const std::vector<command::Command> commands =
        o.kind == "sequence" ? command::seed_test_sequence() : std::vector<command::Command>{build_command(o)};
    for (const command::Command& c : commands) {
      for (link::TransmitFrame& f : link.plan(c)) {
        // A recording is heard in order: each frame counts as confirmed, as the robot that
        // hears the file would confirm it, so only the first is preceded by a synchronisation.
        link.confirmed(f);
        commands_of.push_back(f.synchronisation ? "" : command::describe(link.as_received(c)));
        frames.push_back(std::move(f));
      }
    }
    what = o.kind == "sequence" ? "the seed's test sequence, " + std::to_string(commands.size()) + " commands"
                                : commands_of.back();
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (o.json) {
      nlohmann::json json = frame_json(frames[i]);
      json["index"] = i;
      if (!commands_of[i].empty()) json["command"] = commands_of[i];
      if (!o.wav.empty()) json["t_ms"] = link.frame_start_ms(i);
      std::cout << json.dump() << '\n';
    } else {
      std::cout << "frame " << i + 1 << '/' << frames.size() << "  " << frame_line(frames[i]) << '\n';
    }
  }
  if (!o.json)
    std::cout << "encodes: " << what << ", " << frames.size() << " frame" << (frames.size() == 1 ? "" : "s")
              << " (profile " << link.name() << ")\n";
  if (!o.wav.empty()) {
    const std::vector<float> audio = link.render(frames);
    physical::write_wav_file(o.wav, audio, link.profile().sample_rate_hz);
    if (!o.json) {
      std::printf("wrote %s: %.2f s at %d Hz\n", o.wav.c_str(),
                  static_cast<double>(audio.size()) / link.profile().sample_rate_hz, link.profile().sample_rate_hz);
    }
  }
  return 0;
}

}  // namespace

void add_encode_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<EncodeOptions>();
  CLI::App* encode =
      app.add_subcommand("encode", "Print the frames of a command (word, frame bits, CRC, tones); --wav renders them");
  encode->add_option(
      "--wav", o->wav,
      "also write the chords to this WAV file (profile timing; fast: each frame then 100 ms for its answer)");
  encode->add_option("--profile", o->profile,
                     "link profile: " + profile_names() + " (default: fast with --key, else seed)");
  encode->add_option("--word", o->word, "encode one raw 12-bit word instead of a command")->check(CLI::Range(0, 4095));
  program::add_key_flags(*encode, o->keys, "DTMFCTL", program::default_user_state_dir());

  CLI::App* drive =
      encode->add_subcommand("drive", "drive forward: DRIVE_FOR_DURATION, or DRIVE_FORWARD without --duration");
  drive->add_option("--speed", o->speed, "speed, percent of the robot's maximum (0..100)")->required();
  drive->add_option("--duration", o->duration, "seconds (0..8); omit to drive until the next command");
  CLI::App* turn = encode->add_subcommand("turn", "turn on the spot: TURN_FOR_DURATION, or TURN without --duration");
  turn->add_option("--rotation", o->rotation, "rotation, percent of the maximum; positive turns left (-100..100)")
      ->required();
  turn->add_option("--duration", o->duration, "seconds (0..8); omit to turn until the next command");
  CLI::App* velocity = encode->add_subcommand(
      "velocity", "live driving (fast): linear and angular speed together, held for a lease (VELOCITY)");
  velocity->add_option("--linear-mps", o->linear_mps, "forward speed, m/s; negative reverses (within the robot's)");
  velocity->add_option("--angular-radps", o->angular_radps, "turn rate, rad/s; positive turns left");
  velocity->add_option("--lease-s", o->lease_s, "how long the robot holds it without a renewal (0.3..2)")
      ->capture_default_str();
  velocity->add_option("--robot", o->robot, "TurtleBot3 model whose limits the speeds are fractions of")
      ->envname("TURTLEBOT3_MODEL")
      ->check(CLI::IsMember({"burger", "waffle", "waffle_pi"}))
      ->capture_default_str();
  encode->add_subcommand("stop", "stop the robot (RESET, STOP)");
  encode->add_subcommand("reset", "return the robot to MODE_SELECT (RESET)");
  encode->add_subcommand("sequence", "the seed's 65-frame system test sequence (its section 10)");
  encode->require_subcommand(0, 1);
  encode->callback([o, encode, &global, &run] {
    const auto chosen = encode->get_subcommands();
    if (!chosen.empty()) o->kind = chosen.front()->get_name();
    if (chosen.empty() == !o->word.has_value()) {
      throw CLI::ValidationError("encode",
                                 "give either a command (drive, turn, velocity, stop, reset, sequence) or --word N");
    }
    run = [o, &global] {
      o->json = global.json;  // one JSON object per frame: word, frame, crc, tones_hz, index
      return run_encode(*o);
    };
  });
}

}  // namespace dtmf::cli
