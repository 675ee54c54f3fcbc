#include "sim/fft_convolver.h"

#include <algorithm>

#include "sim/real_fft.h"

namespace dtmf::sim {

namespace {
constexpr std::size_t kHeadTaps = 64;         // convolved directly: 64 multiply-adds a sample
constexpr std::size_t kFirstStageBlock = 64;  // then blocks of 64, 512, 4096 samples: each stage
constexpr std::size_t kStageGrowth = 8;       // covers taps [block, 8 * block), the last the rest
constexpr std::size_t kLargestBlock = 4096;
}  // namespace

// Taps [first, first + partitions * block) of the response, by uniformly partitioned
// overlap-save with blocks of `block` samples (first >= block, a multiple of it).
struct FftConvolver::Stage {
  std::size_t block;
  std::size_t delay_blocks;  // first / block: input block j feeds partition k in output block j + delay_blocks + k
  std::size_t partitions;
  RealFft fft;
  std::size_t bins;
  std::vector<float> h_re, h_im;        // partitions x bins, split so the multiply-add vectorises
  std::vector<float> ring_re, ring_im;  // spectra of the last input frames, ring of ring_size
  std::size_t ring_size;
  std::size_t blocks_done = 0;  // complete input blocks so far
  FftReal frame;                // [previous block, current block]
  std::size_t fill = 0;         // samples of the current block received
  FftBins spectrum;
  FftReal time;
  std::vector<float> acc_re, acc_im;
  std::vector<float> tail;  // this stage's share of the current output block

  Stage(std::span<const float> h, std::size_t first, std::size_t block_size)
      : block(block_size),
        delay_blocks(first / block_size),
        partitions((h.size() - first + block_size - 1) / block_size),
        fft(2 * block_size),
        bins(block_size + 1),
        h_re(partitions * bins),
        h_im(partitions * bins),
        ring_re((partitions + delay_blocks - 1) * bins, 0.0f),
        ring_im((partitions + delay_blocks - 1) * bins, 0.0f),
        ring_size(partitions + delay_blocks - 1),
        frame(2 * block_size, 0.0f),
        spectrum(bins),
        time(2 * block_size),
        acc_re(bins),
        acc_im(bins),
        tail(block_size, 0.0f) {
    for (std::size_t k = 0; k < partitions; ++k) {
      std::fill(time.begin(), time.end(), 0.0f);
      const std::size_t from = first + k * block;
      const std::size_t to = std::min(h.size(), from + block);
      std::copy(h.begin() + static_cast<std::ptrdiff_t>(from), h.begin() + static_cast<std::ptrdiff_t>(to),
                time.begin());
      fft.forward(time.data(), spectrum.data());
      for (std::size_t b = 0; b < bins; ++b) {
        h_re[k * bins + b] = spectrum[b].real();
        h_im[k * bins + b] = spectrum[b].imag();
      }
    }
  }

  // Adds this stage's output for the next in.size() samples to y.
  void run(std::span<const float> in, std::span<float> y) {
    for (std::size_t i = 0; i < in.size();) {
      const std::size_t m = std::min(in.size() - i, block - fill);
      std::copy(in.begin() + static_cast<std::ptrdiff_t>(i), in.begin() + static_cast<std::ptrdiff_t>(i + m),
                frame.begin() + static_cast<std::ptrdiff_t>(block + fill));
      for (std::size_t j = 0; j < m; ++j) y[i + j] += tail[fill + j];
      fill += m;
      i += m;
      if (fill == block) complete_block();
    }
  }

  void complete_block() {
    fft.forward(frame.data(), spectrum.data());
    const std::size_t j = blocks_done++;
    float* new_re = ring_re.data() + (j % ring_size) * bins;
    float* new_im = ring_im.data() + (j % ring_size) * bins;
    for (std::size_t b = 0; b < bins; ++b) {
      new_re[b] = spectrum[b].real();
      new_im[b] = spectrum[b].imag();
    }
    // Output block j + 1 takes, from partition k, input block j + 1 - delay_blocks - k
    // (blocks before the stream's start are zero: their ring slots were never written).
    std::fill(acc_re.begin(), acc_re.end(), 0.0f);
    std::fill(acc_im.begin(), acc_im.end(), 0.0f);
    for (std::size_t k = 0; k < partitions; ++k) {
      const auto source = static_cast<long long>(j + 1) - static_cast<long long>(delay_blocks + k);
      if (source < 0) break;
      const std::size_t slot = static_cast<std::size_t>(source) % ring_size;
      const float* x_re = ring_re.data() + slot * bins;
      const float* x_im = ring_im.data() + slot * bins;
      const float* g_re = h_re.data() + k * bins;
      const float* g_im = h_im.data() + k * bins;
      for (std::size_t b = 0; b < bins; ++b) {
        acc_re[b] += x_re[b] * g_re[b] - x_im[b] * g_im[b];
        acc_im[b] += x_re[b] * g_im[b] + x_im[b] * g_re[b];
      }
    }
    for (std::size_t b = 0; b < bins; ++b) spectrum[b] = {acc_re[b], acc_im[b]};
    fft.inverse(spectrum.data(), time.data());
    const float scale = 1.0f / static_cast<float>(2 * block);
    for (std::size_t t = 0; t < block; ++t) tail[t] = time[block + t] * scale;
    std::copy(frame.begin() + static_cast<std::ptrdiff_t>(block), frame.end(), frame.begin());
    fill = 0;
  }
};

FftConvolver::FftConvolver(std::span<const float> h) : length_(h.size()) {
  const std::size_t head = std::min(h.size(), kHeadTaps);
  head_.assign(h.rbegin() + static_cast<std::ptrdiff_t>(h.size() - head), h.rend());
  history_.assign(head > 0 ? head - 1 : 0, 0.0f);
  std::size_t first = head;
  for (std::size_t block = kFirstStageBlock; first < h.size(); block *= kStageGrowth) {
    // The last stage takes all that is left; earlier ones up to the next stage's block.
    const bool last = block >= kLargestBlock;
    const std::size_t end = last ? h.size() : std::min(h.size(), block * kStageGrowth);
    stages_.push_back(std::make_unique<Stage>(h.first(end), first, block));
    first = end;
  }
}

FftConvolver::~FftConvolver() = default;
FftConvolver::FftConvolver(FftConvolver&&) noexcept = default;
FftConvolver& FftConvolver::operator=(FftConvolver&&) noexcept = default;

void FftConvolver::process_add(std::span<const float> in, std::span<float> out) {
  // In pieces, so that the history and scratch buffers stay small for any call size.
  constexpr std::size_t kPiece = 4096;
  for (std::size_t i = 0; i < in.size(); i += kPiece) {
    const std::size_t n = std::min(kPiece, in.size() - i);
    push_sample_block(in.subspan(i, n), out.subspan(i, n));
  }
}

void FftConvolver::push_sample_block(std::span<const float> in, std::span<float> out) {
  const std::size_t n = in.size();
  const std::size_t taps = head_.size();
  thread_local std::vector<float> y;
  y.assign(n, 0.0f);
  if (taps > 0) {
    const std::size_t kept = taps - 1;
    history_.resize(kept + n);
    std::copy(in.begin(), in.end(), history_.begin() + static_cast<std::ptrdiff_t>(kept));
    // y[i] = sum_u head_[u] * history_[i + u]: tap by tap, so each output sums in the same
    // order however the stream is split.
    for (std::size_t u = 0; u < taps; ++u) {
      const float g = head_[u];
      const float* x = history_.data() + u;
      for (std::size_t i = 0; i < n; ++i) y[i] += g * x[i];
    }
    std::copy(history_.end() - static_cast<std::ptrdiff_t>(kept), history_.end(), history_.begin());
    history_.resize(kept);
  }
  for (auto& stage : stages_) stage->run(in, y);
  for (std::size_t i = 0; i < n; ++i) out[i] += y[i];
}

}  // namespace dtmf::sim
