// dtmfctl simulate: a recording played through the simulated acoustic channel.
#include <cstdio>
#include <memory>
#include <string>

#include "offline_commands.h"
#include "physical/acoustic_channel.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"

namespace dtmf::cli {

namespace {

struct SimulateOptions {
  std::string input;
  std::string output;
  std::string profile = "seed";
  double distance_m = 1.0;
  std::string noise = "none";
  double noise_dbfs = -60;
  double reverb_rt60_s = 0;
  double clock_ppm = 0;
  std::uint64_t seed = 1;
  double tail_s = 0.5;
};

int run_simulate(const SimulateOptions& o) {
  const LinkProfile& profile = profile_by_name(o.profile);
  physical::ChannelConfig config;
  config.noise = physical::parse_noise(o.noise, o.noise_dbfs);
  config.reverb.rt60_s = o.reverb_rt60_s;
  config.clock_offset_ppm = o.clock_ppm;
  config.seed = o.seed;
  physical::AcousticChannel channel(profile.sample_rate_hz, config);
  channel.add_transmitter(o.distance_m);

  physical::WavFileSource source(o.input, profile.sample_rate_hz);
  physical::WavFileSink sink(o.output, profile.sample_rate_hz);
  std::vector<float> block(8192), heard;
  long long samples = 0;
  // After the input ends, let the room ring out and the farthest sound arrive.
  auto tail = static_cast<long long>(o.tail_s * profile.sample_rate_hz);
  while (true) {
    std::size_t got = source.read(block);
    if (got == 0) {
      if (tail <= 0) break;
      got = static_cast<std::size_t>(std::min<long long>(tail, static_cast<long long>(block.size())));
      std::fill(block.begin(), block.begin() + static_cast<std::ptrdiff_t>(got), 0.0f);
      tail -= static_cast<long long>(got);
    }
    heard.clear();
    channel.process(std::span<const float>(block.data(), got), heard);
    sink.write(heard);
    samples += static_cast<long long>(heard.size());
  }
  sink.drain();
  std::printf("wrote %s: %.2f s heard %.1f m away, noise %s at %.1f dBFS, RT60 %.2f s, clock %+.0f ppm\n",
              o.output.c_str(), static_cast<double>(samples) / profile.sample_rate_hz, o.distance_m,
              o.noise.c_str(), o.noise_dbfs, o.reverb_rt60_s, o.clock_ppm);
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, Action& run) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sim = app.add_subcommand("simulate", "Play a recording through the simulated acoustic channel into another");
  sim->add_option("input", o->input, "what the loudspeaker plays")->required();
  sim->add_option("output", o->output, "what the microphone records (16-bit WAV)")->required();
  sim->add_option("--profile", o->profile, "link profile (sets the sample rate): " + profile_names())->capture_default_str();
  sim->add_option("--distance", o->distance_m, "loudspeaker to microphone, metres (> 0)")->capture_default_str()
      ->check(CLI::PositiveNumber);
  sim->add_option("--noise", o->noise, "none, white, pink, or a recording to loop (speech, music)")->capture_default_str();
  sim->add_option("--noise-dbfs", o->noise_dbfs, "noise level, dBFS RMS")->capture_default_str();
  sim->add_option("--reverb-rt60", o->reverb_rt60_s, "room reverberation time, seconds (0: none)")->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  sim->add_option("--clock-ppm", o->clock_ppm, "microphone clock offset, parts per million")->capture_default_str()
      ->check(CLI::Range(-10000.0, 10000.0));
  sim->add_option("--seed", o->seed, "random seed for the noise")->capture_default_str();
  sim->callback([o, &run] { run = [o] { return run_simulate(*o); }; });
}

}  // namespace dtmf::cli
