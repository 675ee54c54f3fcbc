// dtmfctl simulate: a recording played through the simulated acoustic channel.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "offline_commands.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "sim/acoustic_channel.h"
#include "sim/channel_flags.h"

namespace dtmf::cli {

namespace {

struct SimulateOptions {
  std::string input;
  std::string output;
  std::string profile = "seed";
  sim::ChannelFlags channel;
  double tail_s = 0.5;
};

int run_simulate(const SimulateOptions& o, bool json) {
  const LinkProfile& profile = profile_by_name(o.profile);
  const sim::ChannelSetup setup = sim::channel_setup(o.channel);
  const auto channel = sim::make_channel(setup, profile.sample_rate_hz);

  physical::WavFileSource source(o.input, profile.sample_rate_hz);
  physical::WavFileSink sink(o.output, profile.sample_rate_hz);
  std::vector<float> block(8192), heard;
  long long samples = 0, clipped = 0;
  // After the input ends, let the room ring out and the farthest sound arrive.
  auto tail = static_cast<long long>((o.tail_s + channel->ring_out_s()) * profile.sample_rate_hz);
  while (true) {
    std::size_t got = source.read(block);
    if (got == 0) {
      if (tail <= 0) break;
      got = static_cast<std::size_t>(std::min<long long>(tail, static_cast<long long>(block.size())));
      std::fill(block.begin(), block.begin() + static_cast<std::ptrdiff_t>(got), 0.0f);
      tail -= static_cast<long long>(got);
    }
    heard.clear();
    channel->process(std::span<const float>(block.data(), got), heard);
    for (float s : heard) clipped += std::abs(s) > 1.0f ? 1 : 0;
    sink.write(heard);
    samples += static_cast<long long>(heard.size());
  }
  sink.drain();
  const double heard_s = static_cast<double>(samples) / profile.sample_rate_hz;
  if (json) {
    std::printf("%s\n", nlohmann::json{{"output", o.output},
                                       {"heard_s", heard_s},
                                       {"channel", sim::describe_channel(setup, *channel)},
                                       {"clipped_samples", clipped}}
                            .dump()
                            .c_str());
  } else {
    std::printf("wrote %s: %.2f s heard through %s\n", o.output.c_str(), heard_s,
                sim::describe_channel(setup, *channel).c_str());
  }
  // A clipped recording fails for its level, not for the room: say so.
  if (clipped > 0) {
    std::fprintf(
        stderr,
        "dtmfctl: warning: %lld samples (%.2f %%) were beyond full scale and clipped in %s: play the input "
        "quieter or from farther away (a measured room's response, its direct sound scaled to a unit impulse at 1 m, "
        "passes 6 to 16 dB more power at 4.5-16 kHz than 1 m of free field: its reverberation)\n",
        clipped, 100.0 * static_cast<double>(clipped) / static_cast<double>(std::max(samples, 1LL)), o.output.c_str());
  }
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sim =
      app.add_subcommand("simulate", "Play a recording through the simulated acoustic channel into another");
  sim->add_option("input", o->input, "what the loudspeaker plays")->required();
  sim->add_option("output", o->output, "what the microphone records (16-bit WAV)")->required();
  sim->add_option("--profile", o->profile, "link profile (sets the sample rate): " + profile_names())
      ->capture_default_str();
  sim::add_channel_flags(*sim, o->channel);
  sim->footer(
      "The channel: the loudspeaker's response, then free field (delay, 1/d, air absorption) or a room, then the\n"
      "microphone's response, noise, whines, clock offset. A room is measured (--rir: its response already holds\n"
      "its propagation, --distance only scales the level by 1/d) or an image-source shoebox (--room: positions decide\n"
      "delay and level; --distance places the loudspeaker that far from the microphone, --speaker-at exactly).\n"
      "Levels: the input is the level heard 1 m away in free field. A measured room's direct sound is scaled to a\n"
      "unit impulse; its reverberation adds 6 to 16 dB in 4.5-16 kHz (bench/rirs/README.md), so a loud input may\n"
      "clip: play it quieter or from farther away (a warning says when the output clipped).\n"
      "Examples:\n"
      "  dtmfctl simulate in.wav out.wav --rir bench/rirs/seminar_room_clap.wav --distance 3\n"
      "  dtmfctl simulate in.wav out.wav --room 7x9x3 --room-rt60 1.2 --distance 5 --mic-response cheap-mic\n"
      "  dtmfctl simulate in.wav out.wav --room 4x5x2.7 --wall-reflection 125:0.8,4000:0.9 --wall-reflection "
      "floor=0.98 \\\n"
      "      --speaker-at 3,4,0.8 --mic-at 1,1.5,0.05 --whine 9000:-45 --radial-speed-mps 0.22\n"
      "docs/protocol.md section 7 says what each effect models and why.");
  sim->callback([o, &run, &global] { run = [o, &global] { return run_simulate(*o, global.json); }; });
}

}  // namespace dtmf::cli
