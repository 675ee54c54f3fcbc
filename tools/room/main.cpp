// dtmf-room: the simulated acoustic channel (protocol/physical/acoustic_channel.h) as a
// streaming filter, so that real processes can talk through a modelled room.
//
//   parec ... --format=float32le | dtmf-room --distance-m 7 | pacat ... --format=float32le
//
// Why: the PulseAudio air joins the sender and the robot by a perfect wire. To repeat the
// seed's experiments (1, 4, 7, 10 m, noise) with the real programs, scripts/experiments
// puts this filter between the sender's loudspeaker sink and the robot's microphone (and
// back): distance delay, 1/d spreading, air absorption, reverberation, noise, clock offset;
// or a measured room (--rir) or an image-source room (--room), device responses, whines,
// radial motion — the flags of common/channel_flags.h, the same as `dtmfctl simulate`'s.
// For the way back run a second dtmf-room with the same room flags: a room's response is
// reciprocal (docs/protocol.md §7), so the ACK crosses the same room as the command.
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

#include "channel_flags.h"
#include "physical/acoustic_channel.h"
#include "program_main.h"

namespace {

static_assert(sizeof(float) == 4, "float32 samples");

struct Flags {
  dtmf::program::ChannelFlags channel;
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
  const auto setup = dtmf::program::channel_setup(f.channel);
  const auto channel = dtmf::program::make_channel(setup, f.sample_rate_hz);
  std::fprintf(stderr, "dtmf-room: %s\n", dtmf::program::describe_channel(setup, *channel).c_str());

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
    channel->process(std::span<const float>(block.data(), block.size()), out);
    write_all(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(float));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGPIPE, SIG_IGN);  // a closed reader is a write error (exit 1), not a crash
  Flags f;
  CLI::App app{"dtmf-room: raw mono float32le audio on stdin -> the simulated acoustic channel -> stdout"};
  f.channel.reverb_rt60_s = 0.3;  // this filter's default room since scripts/experiments began
  dtmf::program::add_channel_flags(app, f.channel);
  app.add_option("--rate", f.sample_rate_hz, "sample rate, Hz")->check(CLI::Range(8000, 192000))->capture_default_str();
  app.add_option("--block-samples", f.block_samples, "most samples processed at a time")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.footer("Exit codes: 0 end of input, 1 a read or write failed, 2 bad usage.");
  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  return dtmf::program::run([&] { return run(f); },
                            [](const std::string& error) { std::fprintf(stderr, "dtmf-room: %s\n", error.c_str()); });
}
