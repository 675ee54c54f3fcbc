// Signal layer: the latest N samples of a stream, analysed every hop.
//
// feed() appends samples and calls back once every `hop` samples with the latest N, oldest
// first, as one contiguous span — the one sliding-window loop every listener shares. The
// stream is taken to be preceded by silence (the window starts as zeros). Samples go into a
// buffer of 5N; only when it is full are the latest N moved back to its start, so the
// window costs one copy of each sample plus one move of N samples every 4N samples.
// The buffer starts on a 64-byte boundary, so when the hop is a multiple of four samples
// every window is 16-byte aligned and an FFT plan can read it in place (bin_bands.cpp).
// Nothing is allocated after construction.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace dtmf::signal {

class SlidingWindow {
 public:
  SlidingWindow(std::size_t size, std::size_t hop)
      : size_(size), hop_(hop), storage_(5 * size + kAlignFloats, 0.0f), end_(size) {
    const auto address = reinterpret_cast<std::uintptr_t>(storage_.data());
    const std::size_t skew = (address / sizeof(float)) % kAlignFloats;
    buffer_ = storage_.data() + (skew == 0 ? 0 : kAlignFloats - skew);
  }
  // A copy would point into the original's buffer; a move takes the buffer along.
  SlidingWindow(const SlidingWindow&) = delete;
  SlidingWindow& operator=(const SlidingWindow&) = delete;
  SlidingWindow(SlidingWindow&&) noexcept = default;
  SlidingWindow& operator=(SlidingWindow&&) noexcept = default;

  // Appends `samples`; after every hop, on_hop() runs with window() and samples_fed() current.
  template <class OnHop>
  void feed(std::span<const float> samples, OnHop&& on_hop) {
    // Ask for all of the block now: its later hops' samples then arrive while the earlier
    // hops are analysed, instead of each hop waiting for memory when it starts copying.
    for (std::size_t i = 0; i < samples.size(); i += 64 / sizeof(float)) __builtin_prefetch(samples.data() + i);
    while (!samples.empty()) {
      const std::size_t take = std::min(samples.size(), hop_ - since_hop_);
      push(samples.first(take));
      samples = samples.subspan(take);
      samples_fed_ += static_cast<long long>(take);
      since_hop_ += take;
      if (since_hop_ == hop_) {
        since_hop_ = 0;
        on_hop();
      }
    }
  }
  // The latest size() samples, oldest first; valid until the next feed().
  std::span<const float> window() const { return {buffer_ + end_ - size_, size_}; }
  long long samples_fed() const { return samples_fed_; }
  void clear() {
    std::fill(buffer_, buffer_ + capacity(), 0.0f);
    end_ = size_;
    since_hop_ = 0;
    samples_fed_ = 0;
  }

 private:
  void push(std::span<const float> samples) {
    while (!samples.empty()) {
      if (end_ == capacity()) {
        std::memmove(buffer_, buffer_ + end_ - size_, size_ * sizeof(float));
        end_ = size_;
      }
      const std::size_t n = std::min(samples.size(), capacity() - end_);
      std::memcpy(buffer_ + end_, samples.data(), n * sizeof(float));
      end_ += n;
      samples = samples.subspan(n);
    }
  }

  static constexpr std::size_t kAlignFloats = 64 / sizeof(float);
  std::size_t capacity() const { return 5 * size_; }

  std::size_t size_;
  std::size_t hop_;
  std::vector<float> storage_;  // 5N samples, plus room to align them
  float* buffer_;               // the 5N samples, 64-byte aligned, in storage_
  std::size_t end_;             // one past the newest sample
  std::size_t since_hop_ = 0;
  long long samples_fed_ = 0;
};

}  // namespace dtmf::signal
