// dtmf-room: the simulated acoustic channel (protocol/physical/acoustic_channel.h) as a
// streaming filter, so that real processes can talk through a modelled room.
//
//   parec ... --format=float32le | dtmf-room --distance-m 7 | pacat ... --format=float32le
//
// Why: the PulseAudio air joins the sender and the robot by a perfect wire. To repeat the
// seed's experiments (1, 4, 7, 10 m, noise) with the real programs, scripts/experiments
// puts this filter between the sender's loudspeaker sink and the robot's microphone (and
// back): distance delay, 1/d spreading, air absorption, reverberation, noise, clock offset.
//
// It reads raw mono float32 little-endian samples at 48 kHz from stdin, passes whatever
// has arrived (at most --block-samples at a time, so it adds no waiting of its own) through
// one AcousticChannel, and writes the result to stdout at once. EOF on stdin: exit 0.
// Exit codes: 0 end of input, 1 a read or write failed, 2 bad usage.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "physical/acoustic_channel.h"
#include "program_main.h"

namespace {

static_assert(sizeof(float) == 4, "float32 samples");

struct Flags {
  double distance_m = 0;
  double rt60_s = 0.3;
  std::string noise = "none";
  double noise_dbfs = -60;
  double clock_ppm = 0;
  std::uint64_t seed = 1;
  int sample_rate_hz = 48000;
  std::size_t block_samples = 480;
};

// Writes all of `bytes`, retrying after signals and short writes.
void write_all(const char* data, std::size_t bytes) {
  while (bytes > 0) {
    const ssize_t n = ::write(STDOUT_FILENO, data, bytes);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("writing stdout: ") + std::strerror(errno));
    }
    data += n;
    bytes -= static_cast<std::size_t>(n);
  }
}

int run(const Flags& f) {
  dtmf::physical::ChannelConfig config;
  config.noise = dtmf::physical::parse_noise(f.noise, f.noise_dbfs);
  config.reverb.rt60_s = f.rt60_s;
  config.clock_offset_ppm = f.clock_ppm;
  config.seed = f.seed;
  dtmf::physical::AcousticChannel channel(f.sample_rate_hz, config);
  channel.add_transmitter(f.distance_m);

  // Bytes, since a pipe may split a sample; `held` bytes of a partial sample wait in front.
  std::vector<char> in(f.block_samples * sizeof(float));
  std::size_t held = 0;
  std::vector<float> block, out;
  while (true) {
    const ssize_t n = ::read(STDIN_FILENO, in.data() + held, in.size() - held);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("reading stdin: ") + std::strerror(errno));
    }
    if (n == 0) return dtmf::program::kExitOk;  // a trailing partial sample is dropped
    const std::size_t bytes = held + static_cast<std::size_t>(n);
    const std::size_t samples = bytes / sizeof(float);
    block.resize(samples);
    std::memcpy(block.data(), in.data(), samples * sizeof(float));
    held = bytes - samples * sizeof(float);
    std::memmove(in.data(), in.data() + samples * sizeof(float), held);
    if (samples == 0) continue;
    out.clear();
    channel.process(std::span<const float>(block.data(), block.size()), out);
    write_all(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(float));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGPIPE, SIG_IGN);  // a closed reader is a write error (exit 1), not a crash
  Flags f;
  CLI::App app{"dtmf-room: raw mono float32le audio on stdin -> the simulated acoustic channel -> stdout"};
  const CLI::Validator positive(
      [](std::string& text) -> std::string {
        try {
          std::size_t end = 0;
          const double v = std::stod(text, &end);
          if (end == text.size() && std::isfinite(v) && v > 0) return "";
        } catch (const std::exception&) {
        }
        return "must be a distance in metres greater than 0, not '" + text + "'";
      },
      "> 0");
  app.add_option("--distance-m", f.distance_m, "loudspeaker to microphone, metres (> 0)")
      ->required()->check(positive);
  app.add_option("--rt60-s", f.rt60_s, "room reverberation time, seconds (0: none)")
      ->check(CLI::Range(0.0, 10.0))->capture_default_str();
  app.add_option("--noise", f.noise, "noise added at the microphone")
      ->check(CLI::IsMember({"none", "white", "pink"}))->capture_default_str();
  app.add_option("--noise-dbfs", f.noise_dbfs, "noise level, dBFS RMS")
      ->check(CLI::Range(-200.0, 0.0))->capture_default_str();
  app.add_option("--clock-ppm", f.clock_ppm, "microphone clock offset, parts per million")
      ->check(CLI::Range(-10000.0, 10000.0))->capture_default_str();
  app.add_option("--seed", f.seed, "random seed of the noise")->capture_default_str();
  app.add_option("--rate", f.sample_rate_hz, "sample rate, Hz")->check(CLI::Range(8000, 192000))->capture_default_str();
  app.add_option("--block-samples", f.block_samples, "most samples processed at a time")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  app.footer("Exit codes: 0 end of input, 1 a read or write failed, 2 bad usage.");
  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  return dtmf::program::run([&] { return run(f); },
                            [](const std::string& error) { std::fprintf(stderr, "dtmf-room: %s\n", error.c_str()); });
}
