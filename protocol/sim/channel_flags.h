// The simulated acoustic channel's command-line flags, one definition for every program
// that runs sound through it (dtmfctl simulate, dtmf-room): distance, noise, the old
// reverberator, a measured room (--rir) or an image-source room (--room and its walls,
// positions and RT60), microphone and loudspeaker responses, whines, clock offset and
// radial motion. add_channel_flags() declares them on a CLI11 app; channel_setup() turns
// what was given into a sim::ChannelConfig, refusing combinations that make no sense
// with a message naming the flags. It lives beside the simulator it configures; the
// simulator's classes parse the values themselves (room_spec.h, frequency_response.h,
// whines.h) and know nothing of flags. Header-only (CLI11), so dtmf_sim links no flag
// parser: a program that includes it has CLI11 already.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/acoustic_channel.h"
#include "sim/room_spec.h"

namespace dtmf::sim {

struct ChannelFlags {
  double distance_m = 1.0;
  std::string noise = "none";
  double noise_dbfs = -60;
  double reverb_rt60_s = 0;
  double clock_ppm = 0;
  std::uint64_t seed = 1;
  std::string rir;
  std::string room;
  std::vector<std::string> reflections;
  double room_rt60_s = 0;
  std::string speaker_at, mic_at;
  std::uint64_t room_seed = 1;
  std::string mic_response = "flat", speaker_response = "flat";
  std::vector<std::string> whines;
  double radial_speed_mps = 0;
  std::string radial_range_m = "0.5:20";
  // Set by add_channel_flags(): whether these were given or are defaults.
  const CLI::Option* distance_given = nullptr;
  const CLI::Option* reverb_given = nullptr;
};

// Declares the flags on `app`; the values in `f` are the defaults shown in --help.
inline void add_channel_flags(CLI::App& app, ChannelFlags& f) {
  f.distance_given =
      app.add_option("--distance,--distance-m", f.distance_m,
                     "loudspeaker to microphone, metres (> 0); with --rir it only scales the level (1/d)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
  app.add_option("--noise", f.noise, "noise at the microphone: none, white, pink, or a recording to loop")
      ->capture_default_str();
  app.add_option("--noise-dbfs", f.noise_dbfs, "noise level, dBFS RMS")
      ->check(CLI::Range(-200.0, 0.0))
      ->capture_default_str();
  f.reverb_given = app.add_option("--reverb-rt60,--rt60-s", f.reverb_rt60_s,
                                  "the old diffuse reverberator's RT60, seconds (0: none; not with --rir or --room)")
                       ->check(CLI::Range(0.0, 10.0))
                       ->capture_default_str();
  app.add_option("--clock-ppm", f.clock_ppm, "microphone clock offset, parts per million (+-10000)")
      ->check(CLI::Range(-10000.0, 10000.0))
      ->capture_default_str();
  app.add_option("--seed", f.seed, "random seed of the noise and the whines' phases")->capture_default_str();
  app.add_option("--rir", f.rir,
                 "a measured room: an impulse response file (any rate; channel 0), e.g. bench/rirs/*.wav");
  app.add_option("--room", f.room, "an image-source (shoebox) room, LxWxH metres, e.g. 7x9x3");
  app.add_option(
         "--wall-reflection", f.reflections,
         "reflection coefficient in [0, 1): 0.9, or per band 125:0.7,4000:0.9; for the walls and ceiling, or "
         "SURFACES=... (walls, ceiling, floor, x0, x1, y0, y1, all; joined by +); repeatable; default walls and "
         "ceiling 0.9, floor 0.97")
      ->take_all()
      ->allow_extra_args(false);
  app.add_option("--room-rt60", f.room_rt60_s,
                 "tune the walls and ceiling of --room to this broadband RT60 (T20), 0.1 to 2.5 s")
      ->check(CLI::Range(0.1, 2.5));
  app.add_option("--speaker-at", f.speaker_at, "loudspeaker position in --room, x,y,z metres (instead of --distance)");
  app.add_option("--mic-at", f.mic_at, "microphone position in --room, x,y,z metres (default 5 cm above the floor)");
  app.add_option("--room-seed", f.room_seed, "random seed of --room's image positions (the same both ways)")
      ->capture_default_str();
  app.add_option("--mic-response", f.mic_response,
                 "microphone frequency response: " + sim::response_preset_names() + ", Hz:dB,... or a file of them")
      ->capture_default_str();
  app.add_option("--speaker-response", f.speaker_response, "loudspeaker frequency response, as --mic-response")
      ->capture_default_str();
  app.add_option("--whine", f.whines, "a steady tone at the microphone, HZ:DBFS (RMS), e.g. 9000:-45; repeatable")
      ->take_all()
      ->allow_extra_args(false);
  app.add_option("--radial-speed-mps", f.radial_speed_mps,
                 "the loudspeaker moves away (> 0) or closer (< 0) at this speed, m/s (Doppler)")
      ->check(CLI::Range(-50.0, 50.0))
      ->capture_default_str();
  app.add_option("--radial-range-m", f.radial_range_m, "MIN:MAX metres the moving loudspeaker turns back at")
      ->capture_default_str();
}

struct ChannelSetup {
  sim::ChannelConfig config;
  std::optional<sim::Point3> speaker_at;
  double distance_m = 1;
};

namespace channel_flags_detail {
// Runs `parse`, prefixing any complaint with the flag it came from.
template <typename F>
auto from_flag(const char* flag, F parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(flag) + ": " + e.what());
  }
}
}  // namespace channel_flags_detail

// The channel the flags describe. std::invalid_argument naming the flags for anything
// that cannot work together or a value that cannot be read.
inline ChannelSetup channel_setup(const ChannelFlags& f) {
  using channel_flags_detail::from_flag;
  ChannelSetup s;
  sim::ChannelConfig& c = s.config;
  s.distance_m = f.distance_m;
  c.noise = sim::parse_noise(f.noise, f.noise_dbfs);
  c.clock_offset_ppm = f.clock_ppm;
  c.seed = f.seed;
  c.mic_response = from_flag("--mic-response", [&] { return sim::parse_response(f.mic_response); });
  c.speaker_response = from_flag("--speaker-response", [&] { return sim::parse_response(f.speaker_response); });
  for (const auto& w : f.whines) c.whines.push_back(from_flag("--whine", [&] { return sim::parse_whine(w); }));
  c.motion.speed_mps = f.radial_speed_mps;
  const auto range = from_flag("--radial-range-m", [&] { return sim::parse_range(f.radial_range_m); });
  c.motion.min_distance_m = range.first;
  c.motion.max_distance_m = range.second;

  const bool distance_given = f.distance_given && f.distance_given->count() > 0;
  const bool reverb_given = f.reverb_given && f.reverb_given->count() > 0;
  const bool room_only = !f.reflections.empty() || f.room_rt60_s > 0 || !f.speaker_at.empty() || !f.mic_at.empty();
  if (!f.rir.empty() && !f.room.empty())
    throw std::invalid_argument("--rir and --room: a room is measured or simulated, give one");
  if (f.room.empty() && room_only) {
    throw std::invalid_argument(
        "--wall-reflection, --room-rt60, --speaker-at and --mic-at describe an image-source room: give --room too");
  }
  if ((!f.rir.empty() || !f.room.empty()) && reverb_given && f.reverb_rt60_s > 0) {
    throw std::invalid_argument(
        "--reverb-rt60 and a room (--rir or --room): the room reverberates already; for a "
        "reverberation time in a simulated room give --room-rt60");
  }
  if (f.rir.empty() && f.room.empty()) c.reverb.rt60_s = f.reverb_rt60_s;  // the old reverberator, as before
  c.room.rir_file = f.rir;
  if (!f.room.empty()) {
    sim::ShoeboxRoom box;
    box.size_m = from_flag("--room", [&] { return sim::parse_room_size(f.room); });
    for (const auto& spec : f.reflections) {
      const auto surfaces = from_flag("--wall-reflection", [&] { return sim::apply_reflection(box, spec); });
      for (sim::Surface surface : surfaces) {
        if (f.room_rt60_s > 0 && surface != sim::kFloor) {
          throw std::invalid_argument("--wall-reflection '" + spec +
                                      "' and --room-rt60: the RT60 sets the walls and "
                                      "ceiling itself; with it give only the floor's (floor=0.95)");
        }
      }
    }
    c.room.shoebox = box;
    c.room.target_rt60_s = f.room_rt60_s;
    c.room.seed = f.room_seed;
    if (!f.mic_at.empty()) c.room.mic_at = from_flag("--mic-at", [&] { return sim::parse_position(f.mic_at); });
    if (!f.speaker_at.empty()) {
      if (distance_given)
        throw std::invalid_argument(
            "--distance and --speaker-at: give the loudspeaker's distance or its position, not both");
      s.speaker_at = from_flag("--speaker-at", [&] { return sim::parse_position(f.speaker_at); });
    }
  }
  return s;
}

// The channel with its one loudspeaker; std::invalid_argument naming the flags (a
// loudspeaker outside the room, a moving one outside its range...).
inline std::unique_ptr<sim::AcousticChannel> make_channel(const ChannelSetup& s, int sample_rate_hz) {
  try {
    auto channel = std::make_unique<sim::AcousticChannel>(sample_rate_hz, s.config);
    if (s.speaker_at)
      channel->add_transmitter_at(*s.speaker_at);
    else
      channel->add_transmitter(s.distance_m);
    return channel;
  } catch (const std::invalid_argument& e) {
    const std::string flags = s.config.room.shoebox
                                  ? "--room, --speaker-at, --mic-at, --distance, --room-rt60 or --radial-range-m"
                                  : "--distance, --rir or --radial-range-m";
    throw std::invalid_argument(std::string(e.what()) + " (check " + flags + ")");
  }
}

// One line on what the channel does, for a program's report.
inline std::string describe_channel(const ChannelSetup& s, const sim::AcousticChannel& channel) {
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  const sim::ChannelConfig& c = s.config;
  std::string text;
  if (const auto* room = channel.room()) {
    text = room->describe();
    if (s.speaker_at)
      text += ", loudspeaker at (" + number(s.speaker_at->x) + ", " + number(s.speaker_at->y) + ", " +
              number(s.speaker_at->z) + ") m";
    else
      text += ", loudspeaker " + number(s.distance_m) + " m away" + (c.room.rir_file.empty() ? "" : " (level 1/d)");
  } else {
    text = "free field, " + number(s.distance_m) + " m" +
           (c.reverb.rt60_s > 0 ? ", reverberator RT60 " + number(c.reverb.rt60_s) + " s" : "");
  }
  if (c.noise.kind != sim::NoiseKind::None) text += ", noise at " + number(c.noise.level_dbfs) + " dBFS";
  if (!c.mic_response.flat()) text += ", microphone " + c.mic_response.name;
  if (!c.speaker_response.flat()) text += ", loudspeaker response " + c.speaker_response.name;
  for (const auto& w : c.whines)
    text += ", whine " + number(w.frequency_hz) + " Hz at " + number(w.level_dbfs) + " dBFS";
  if (c.clock_offset_ppm != 0) text += ", clock " + number(c.clock_offset_ppm) + " ppm";
  if (c.motion.speed_mps != 0) {
    text += ", moving " + number(c.motion.speed_mps) + " m/s within " + number(c.motion.min_distance_m) + "-" +
            number(c.motion.max_distance_m) + " m";
  }
  return text;
}

}  // namespace dtmf::sim
