// dtmfctl decode: a recording through the robot's receive path, printing every frame heard;
// with --replies, through the sender's ear instead, printing every ACK and NACK heard.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame_output.h"
#include "link/link.h"
#include "offline_commands.h"
#include "physical/wav_file.h"
#include "security/link_key.h"

namespace dtmf::cli {

namespace {

struct DecodeOptions {
  bool json = false;
  bool replies = false;
  std::string profile = "seed";
  std::string file;
  std::string key_file;
};

// A robot's view of the recording: with --key, checking MACs, the counters starting afresh
// (in memory: decoding changes no robot's state).
std::unique_ptr<link::Link> decode_link(const DecodeOptions& o) {
  link::LinkOptions options;
  if (!o.key_file.empty()) options.key = security::LinkKey::load(o.key_file);
  return link::make_link(profile_by_name(o.profile), options);
}

// Feeds the recording, block by block, then a second of silence: a recording may stop as its
// last frame or answer does, but a robot or a sender would go on listening (a failed frame's
// NACK waits for its cluster to settle, 13 hops; a failed window's second look comes two hops
// after it), so every verdict gets its time.
template <class Feed>
void feed_recording(physical::WavFileSource& source, std::vector<float>& block, int sample_rate_hz, Feed&& feed) {
  while (const std::size_t got = source.read(block)) feed(std::span<const float>(block.data(), got));
  std::fill(block.begin(), block.end(), 0.0f);
  for (std::size_t left = static_cast<std::size_t>(sample_rate_hz); left > 0;) {
    const std::size_t n = std::min(block.size(), left);
    feed(std::span<const float>(block.data(), n));
    left -= n;
  }
}

// The recording through the profile's receive path; prints every verdict, then (unless
// --json) the count.
int run_decode(const DecodeOptions& o) {
  const auto made = decode_link(o);
  const link::Link& link = *made;
  const LinkProfile& profile = link.profile();
  physical::WavFileSource source(o.file, profile.sample_rate_hz, profile.min_recording_rate_hz());
  const auto receiver = link.receiver();
  std::vector<float> block(static_cast<std::size_t>(link.receiver_block_samples()) * 8);
  int frames = 0, intact = 0, authenticated = 0, refused = 0;
  const auto print = [&](std::span<const link::Reception> heard) {
    for (const link::Reception& r : heard) {
      ++frames;
      intact += r.intact ? 1 : 0;
      authenticated += r.authenticated ? 1 : 0;
      refused += r.refusal == link::RefusalReason::Authentication ? 1 : 0;
      if (o.json)
        std::cout << reception_json(r).dump() << '\n';
      else
        std::printf("%s\n", reception_line(r).c_str());
    }
  };
  feed_recording(source, block, profile.sample_rate_hz, [&](std::span<const float> b) { print(receiver->feed(b)); });
  if (!o.json) {
    std::printf("%s: %d frame%s heard, %d intact, %d failed the check (profile %s)\n", source.describe().c_str(),
                frames, frames == 1 ? "" : "s", intact, frames - intact, profile.name.c_str());
    if (link.keyed()) {
      std::printf("key %s: %d MAC%s held, %d frame%s refused for authentication\n",
                  made->options().key->id_hex().c_str(), authenticated, authenticated == 1 ? "" : "s", refused,
                  refused == 1 ? "" : "s");
    }
  }
  return 0;
}

// The recording through the profile's reply ear (what the sender hears after each frame).
int run_decode_replies(const DecodeOptions& o) {
  const auto made = decode_link(o);
  const link::Link& link = *made;
  const LinkProfile& profile = link.profile();
  physical::WavFileSource source(o.file, profile.sample_rate_hz, profile.min_recording_rate_hz());
  const auto ear = link.answer_listener();
  std::vector<float> block(static_cast<std::size_t>(link.answer_block_samples()));
  int acks = 0, nacks = 0;
  // A tag chord is read in several windows; those less than a chord apart are one answer.
  const double tag_chord_ms = profile.timing.chord_ms;
  double last_tag_ms = -1e9;
  feed_recording(source, block, profile.sample_rate_hz, [&](std::span<const float> b) {
    for (const link::Answer& a : ear->feed(b)) {
      // A tagged ACK's tones as heard, -1 where a band was not (the sender counts the bands
      // that spell the tag it waits for; offline there is no frame to wait for).
      const auto tag = link::spelled_tag(a);
      if (tag) {
        const bool again = a.heard_ms - last_tag_ms < tag_chord_ms;
        last_tag_ms = a.heard_ms;
        if (again) continue;
      }
      (a.ack ? acks : nacks) += 1;
      std::string spelt;
      if (tag) {
        for (const int t : *tag) spelt += (spelt.empty() ? "" : ".") + (t < 0 ? std::string("-") : std::to_string(t));
      }
      if (o.json) {
        nlohmann::json j{{"t_ms", a.heard_ms}, {"reply", a.ack ? "ack" : "nack"}};
        if (a.sequence) j["sequence"] = *a.sequence;
        if (tag) {
          j["tag_tones"] = *tag;
        } else {
          j["lane"] = a.lane;
        }
        std::cout << j.dump() << '\n';
      } else if (tag) {
        std::printf("t=%.3f s ACK tag tones %s\n", a.heard_ms / 1000.0, spelt.c_str());
      } else {
        std::printf("t=%.3f s %s%s lane %d\n", a.heard_ms / 1000.0, a.ack ? "ACK" : "NACK",
                    a.sequence ? (" seq " + std::to_string(*a.sequence)).c_str() : "", a.lane);
      }
    }
  });
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
  decode->add_option("--key", o->key_file, "check each frame's MAC with this key (dtmfctl keygen)")
      ->envname("DTMFCTL_KEY_FILE");
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
