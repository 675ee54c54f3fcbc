// dtmfctl decode: a recording through the robot's receive path; prints every frame heard.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "frame_output.h"
#include "link/command_frame_path.h"
#include "link/receiver_path.h"
#include "reliability/command_frame.h"
#include "offline_commands.h"
#include "physical/wav_file.h"

namespace dtmf::cli {

namespace {

struct DecodeOptions {
  bool json = false;
  std::string profile = "seed";
  std::string file;
};

// The recording through `path` (either profile's receive path); `print` shows one verdict and
// says whether it was intact. Ends with the count, unless --json.
template <class Path, class Print>
int decode_file(const DecodeOptions& o, const LinkProfile& profile, Path& path, Print print) {
  physical::WavFileSource source(o.file, profile.sample_rate_hz, profile.min_recording_rate_hz());
  std::vector<float> block(static_cast<std::size_t>(profile.hop_samples()) * 8);
  int frames = 0, intact = 0;
  while (const std::size_t got = source.read(block)) {
    for (const auto& r : path.feed(std::span<const float>(block.data(), got))) {
      ++frames;
      intact += print(r) ? 1 : 0;
    }
  }
  if (!o.json) {
    std::printf("%s: %d frame%s heard, %d intact, %d failed the CRC (profile %s)\n", source.describe().c_str(), frames,
                frames == 1 ? "" : "s", intact, frames - intact, profile.name.c_str());
  }
  return 0;
}

// The fast profile: every verdict, with the command an intact frame carries.
bool print_command_frame(const DecodeOptions& o, const link::ReceivedCommandFrame& r) {
  const std::string bits = reliability::bit_string(r.bits, reliability::kCommandFrameBits);
  const std::string what = r.command ? command::describe(*r.command) : r.repeat ? "repeat, not executed again"
                                                                       : r.error.empty() ? "(rejected)" : r.error;
  if (o.json) {
    nlohmann::json json{{"t_ms", std::lround(r.start_ms)}, {"heard_ms", std::lround(r.heard_ms)}, {"frame", bits},
                        {"crc_ok", r.frame.has_value()}, {"what", what}};
    if (r.frame) json["sequence"] = r.frame->sequence;
    std::cout << json.dump() << '\n';
  } else {
    std::printf("%8.3f s  %s  CRC %s  %s\n", r.start_ms / 1000.0, bits.c_str(), r.frame ? "ok  " : "FAIL", what.c_str());
  }
  return r.frame.has_value();
}

// The seed profile: every frame, with what its word did to the command state.
bool print_word_frame(const DecodeOptions& o, const LinkProfile& profile, const link::ReceivedFrame& r) {
  const link::PlannedFrame as_planned{reliability::frame_word(r.frame), r.frame, signal::chord_for(profile.tones, r.frame)};
  if (o.json) {
    nlohmann::json json = frame_json(as_planned);
    json["t_ms"] = std::lround(r.start_ms);
    json["heard_ms"] = std::lround(r.heard_ms);
    json["crc_ok"] = r.crc_ok;
    if (r.event) json["event"] = event_json(*r.event);
    std::cout << json.dump() << '\n';
  } else {
    std::printf("%8.3f s  %s  CRC %s  %s\n", r.start_ms / 1000.0, frame_line(as_planned).c_str(),
                r.crc_ok ? "ok  " : "FAIL", r.event ? event_text(*r.event).c_str() : "(rejected)");
  }
  return r.crc_ok;
}

int run_decode(const DecodeOptions& o) {
  const LinkProfile& profile = profile_by_name(o.profile);
  if (profile.frame_format == FrameFormat::Command48) {
    link::CommandFramePath path(profile);
    return decode_file(o, profile, path, [&](const link::ReceivedCommandFrame& r) { return print_command_frame(o, r); });
  }
  link::ReceiverPath path(profile);
  return decode_file(o, profile, path, [&](const link::ReceivedFrame& r) { return print_word_frame(o, profile, r); });
}

}  // namespace

void add_decode_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<DecodeOptions>();
  CLI::App* decode = app.add_subcommand("decode", "Run the robot's receive path on a recording and print each frame heard");
  decode->add_option("--profile", o->profile, "link profile: " + profile_names())->capture_default_str();
  decode->add_option("file", o->file, "recording (WAV, FLAC, AIFF; any rate of at least twice the top tone)")->required();
  decode->callback([o, &global, &run] {
    run = [o, &global] {
      o->json = global.json;  // one JSON object per frame: t_ms, heard_ms, word, frame, crc, crc_ok, tones_hz, event
      return run_decode(*o);
    };
  });
}

}  // namespace dtmf::cli
