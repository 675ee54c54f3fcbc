// Physical layer, room helpers: streaming convolution with a long impulse response (a room's,
// up to a few seconds), with no latency and at many times real time.
//
// How: the response is cut into pieces convolved in different ways, all summed per sample.
//   - its first kHeadTaps taps directly, sample by sample (this is what keeps the latency
//     at zero: the direct sound of a response may sit at its very first sample);
//   - the rest by uniformly partitioned overlap-save in stages of growing block size
//     (64, 512, 4096 samples): a stage whose first tap lies at least one block into the
//     response needs only input blocks that are already complete, so each block's
//     contribution is computed (one FFT of the input, a multiply-add per partition in the
//     frequency domain, one inverse FFT) at the moment the block before it is complete.
// Every FFT happens at a fixed sample count from the start of the stream, never at a call
// boundary, so the output is the same for any split of the input into process() calls.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace dtmf::sim {

class FftConvolver {
 public:
  explicit FftConvolver(std::span<const float> impulse_response);
  ~FftConvolver();
  FftConvolver(FftConvolver&&) noexcept;
  FftConvolver& operator=(FftConvolver&&) noexcept;

  // Adds (response * input) to `out`, one output sample per input sample (out.size() must
  // equal in.size()).
  void process_add(std::span<const float> in, std::span<float> out);

  std::size_t length() const { return length_; }

 private:
  struct Stage;
  void push_sample_block(std::span<const float> in, std::span<float> out);

  std::size_t length_;
  std::vector<float> head_;     // the first taps, reversed for a forward dot product
  std::vector<float> history_;  // the last head_.size() - 1 inputs, then the current chunk
  std::vector<std::unique_ptr<Stage>> stages_;
};

}  // namespace dtmf::sim
