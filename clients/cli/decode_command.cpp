// dtmfctl decode: a recording through the robot's receive path, printing every frame heard;
// with --replies, through the sender's ear instead, printing every ACK and NACK heard.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "frame_output.h"
#include "link/link.h"
#include "offline_commands.h"
#include "physical/wav_file.h"

namespace dtmf::cli {

namespace {

struct DecodeOptions {
  bool json = false;
  bool replies = false;
  std::string profile = "seed";
  std::string file;
};

// The recording through the profile's receive path; prints every verdict, then (unless
// --json) the count.
int run_decode(const DecodeOptions& o) {
  const link::Link& link = link::link_by_name(o.profile);
  const LinkProfile& profile = link.profile();
  physical::WavFileSource source(o.file, profile.sample_rate_hz, profile.min_recording_rate_hz());
  const auto receiver = link.receiver();
  std::vector<float> block(static_cast<std::size_t>(link.receiver_block_samples()) * 8);
  int frames = 0, intact = 0;
  while (const std::size_t got = source.read(block)) {
    for (const link::Reception& r : receiver->feed(std::span<const float>(block.data(), got))) {
      ++frames;
      intact += r.intact ? 1 : 0;
      if (o.json)
        std::cout << reception_json(r).dump() << '\n';
      else
        std::printf("%s\n", reception_line(r).c_str());
    }
  }
  if (!o.json) {
    std::printf("%s: %d frame%s heard, %d intact, %d failed the check (profile %s)\n", source.describe().c_str(),
                frames, frames == 1 ? "" : "s", intact, frames - intact, profile.name.c_str());
  }
  return 0;
}

// The recording through the profile's reply ear (what the sender hears after each frame).
int run_decode_replies(const DecodeOptions& o) {
  const link::Link& link = link::link_by_name(o.profile);
  const LinkProfile& profile = link.profile();
  physical::WavFileSource source(o.file, profile.sample_rate_hz, profile.min_recording_rate_hz());
  const auto ear = link.answer_listener();
  std::vector<float> block(static_cast<std::size_t>(link.answer_block_samples()));
  int acks = 0, nacks = 0;
  while (const std::size_t got = source.read(block)) {
    for (const link::Answer& a : ear->feed(std::span<const float>(block.data(), got))) {
      (a.ack ? acks : nacks) += 1;
      if (o.json) {
        nlohmann::json j{{"t_ms", a.heard_ms}, {"reply", a.ack ? "ack" : "nack"}};
        if (a.sequence) j["sequence"] = *a.sequence;
        std::cout << j.dump() << '\n';
      } else {
        std::printf("t=%.3f s %s%s\n", a.heard_ms / 1000.0, a.ack ? "ACK" : "NACK",
                    a.sequence ? (" seq " + std::to_string(*a.sequence)).c_str() : "");
      }
    }
  }
  if (!o.json) {
    std::printf("%s: %d ACK%s, %d NACK%s heard (profile %s)\n", source.describe().c_str(), acks, acks == 1 ? "" : "s",
                nacks, nacks == 1 ? "" : "s", profile.name.c_str());
  }
  return 0;
}

}  // namespace

void add_decode_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<DecodeOptions>();
  CLI::App* decode =
      app.add_subcommand("decode", "Run the robot's receive path on a recording and print each frame heard");
  decode->add_option("--profile", o->profile, "link profile: " + profile_names())->capture_default_str();
  decode->add_flag(
      "--replies", o->replies,
      "the recording holds the robot's answers: print each ACK / NACK heard (the sender's ear), not frames");
  decode->add_option("file", o->file, "recording (WAV, FLAC, AIFF; any rate of at least twice the top tone)")
      ->required();
  decode->callback([o, &global, &run] {
    run = [o, &global] {
      o->json = global.json;  // one JSON object per frame: t_ms, heard_ms, word, frame, crc, crc_ok, tones_hz, event
      return o->replies ? run_decode_replies(*o) : run_decode(*o);
    };
  });
}

}  // namespace dtmf::cli
