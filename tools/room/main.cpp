// dtmf-room: the simulated acoustic channel (protocol/sim/acoustic_channel.h) as a
// streaming filter, so that real processes can talk through a modelled room.
//
//   parec ... --format=float32le | dtmf-room --distance-m 7 | pacat ... --format=float32le
//
// Why: the PulseAudio air joins the sender and the robot by a perfect wire. To repeat the
// seed's experiments (1, 4, 7, 10 m, noise) with the real programs, scripts/experiments
// puts this filter between the sender's loudspeaker sink and the robot's microphone (and
// back): distance delay, 1/d spreading, air absorption, reverberation, noise, clock offset;
// or a measured room (--rir) or an image-source room (--room), device responses, whines,
// radial motion — the flags of protocol/sim/channel_flags.h, the same as `dtmfctl simulate`'s.
// For the way back run a second dtmf-room with the same room flags: a room's response is
// reciprocal (docs/protocol.md §7), so the ACK crosses the same room as the command.
//
// It reads raw mono float32 little-endian samples at 48 kHz from stdin, passes whatever
// has arrived (at most --block-samples at a time, so it adds no waiting of its own) through
// one AcousticChannel, and writes the result to stdout at once. Input that comes later than
// --max-lag-ms behind the wall clock (after a stall upstream) is dropped (lag_keeper.h).
// EOF on stdin: exit 0.
// Exit codes: 0 end of input, 1 a read or write failed, 2 bad usage.
#include <sys/ioctl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "lag_keeper.h"
#include "program_main.h"
#include "sim/acoustic_channel.h"
#include "sim/channel_flags.h"

namespace {

static_assert(sizeof(float) == 4, "float32 samples");

struct Flags {
  dtmf::sim::ChannelFlags channel;
  int sample_rate_hz = 48000;
  std::size_t block_samples = 480;
  double max_lag_ms = 0;  // 0: keep every sample however late, as a file needs (lag_keeper.h)
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
  const auto setup = dtmf::sim::channel_setup(f.channel);
  const auto channel = dtmf::sim::make_channel(setup, f.sample_rate_hz);
  std::fprintf(stderr, "dtmf-room: %s\n", dtmf::sim::describe_channel(setup, *channel).c_str());

  // Bytes, since a pipe may split a sample; `held` bytes of a partial sample wait in front.
  std::vector<char> in(f.block_samples * sizeof(float));
  std::size_t held = 0;
  std::vector<float> block, out;
  dtmf::room::LagKeeper keeper(f.sample_rate_hz, f.max_lag_ms);
  const auto started = std::chrono::steady_clock::now();
  std::size_t reported_drops = 0;
  // A pipe holds up to 64 KiB, 340 ms of these samples: sound queued in the input pipe
  // (parec delivers a burst at start and after a stall) or in the output pipe (pacat waits)
  // is that much late, for good, since both ends then run at the same pace. Past
  // --max-lag-ms the oldest input is dropped and output that finds the pipe that full is.
  const auto queued_ms = [&](int fd) {
    int bytes = 0;
    // No answer: nothing to judge. (A file answers with what is left of it: files keep the
    // default --max-lag-ms 0.)
    if (::ioctl(fd, FIONREAD, &bytes) != 0) return 0.0;
    return 1000.0 * bytes / static_cast<double>(sizeof(float) * static_cast<std::size_t>(f.sample_rate_hz));
  };
  std::vector<char> discard;
  while (true) {
    if (f.max_lag_ms > 0 && held == 0 && queued_ms(STDIN_FILENO) > f.max_lag_ms) {
      const auto late_samples =
          static_cast<std::size_t>((queued_ms(STDIN_FILENO) - f.max_lag_ms / 10) * f.sample_rate_hz / 1000.0);
      discard.resize(late_samples * sizeof(float));
      const ssize_t got = ::read(STDIN_FILENO, discard.data(), discard.size());
      // A partial sample read here would shift every later sample: keep its bytes in front.
      if (got > 0) {
        held = static_cast<std::size_t>(got) % sizeof(float);
        std::memcpy(in.data(), discard.data() + got - static_cast<ssize_t>(held), held);
        keeper.skip_input(static_cast<std::size_t>(got) / sizeof(float));
      }
    }
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
    if (f.max_lag_ms > 0) {
      const double now_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
      const std::size_t drop = keeper.to_drop(now_ms, samples);
      block.erase(block.begin(), block.begin() + static_cast<std::ptrdiff_t>(drop));
      if (keeper.dropped() >= reported_drops + static_cast<std::size_t>(f.sample_rate_hz)) {
        std::fprintf(stderr, "dtmf-room: %.0f ms of sound dropped so far: it came too late (a full pipe, a stall)\n",
                     1000.0 * static_cast<double>(keeper.dropped()) / f.sample_rate_hz);
        reported_drops = keeper.dropped();
      }
      if (block.empty()) continue;
    }
    out.clear();
    channel->process(std::span<const float>(block.data(), block.size()), out);
    if (f.max_lag_ms > 0 && queued_ms(STDOUT_FILENO) > f.max_lag_ms) {
      keeper.count_dropped_output(out.size());
      continue;
    }
    write_all(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(float));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGPIPE, SIG_IGN);  // a closed reader is a write error (exit 1), not a crash
  Flags f;
  CLI::App app{"dtmf-room: raw mono float32le audio on stdin -> the simulated acoustic channel -> stdout"};
  f.channel.reverb_rt60_s = 0.3;  // this filter's default room since scripts/experiments began
  dtmf::sim::add_channel_flags(app, f.channel);
  app.add_option("--rate", f.sample_rate_hz, "sample rate, Hz")->check(CLI::Range(8000, 192000))->capture_default_str();
  app.add_option("--block-samples", f.block_samples, "most samples processed at a time")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.add_option("--max-lag-ms", f.max_lag_ms,
                 "live bridges: drop sound queued longer than this (full pipes, stalls); 0: never (files)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  app.footer("Exit codes: 0 end of input, 1 a read or write failed, 2 bad usage.");
  if (const auto exit_code = dtmf::program::parse(app, argc, argv)) return *exit_code;
  return dtmf::program::run([&] { return run(f); },
                            [](const std::string& error) { std::fprintf(stderr, "dtmf-room: %s\n", error.c_str()); });
}
