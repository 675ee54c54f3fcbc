// Signal layer: the latest N samples of a stream, analysed every hop.
//
// feed() appends samples and calls back once every `hop` samples with the latest N, oldest
// first, as one contiguous span — the one sliding-window loop every listener shares. The
// stream is taken to be preceded by silence (the window starts as zeros). Samples go into a
// buffer of 5N; only when it is full are the latest N moved back to its start, so the
// window costs one copy of each sample plus one move of N samples every 4N samples.
// Nothing is allocated after construction.
#pragma once

#include <algorithm>
#include <cstring>
#include <span>
#include <vector>

namespace dtmf::signal {

class SlidingWindow {
 public:
  SlidingWindow(std::size_t size, std::size_t hop) : size_(size), hop_(hop), buffer_(5 * size, 0.0f), end_(size) {}

  // Appends `samples`; after every hop, on_hop() runs with window() and samples_fed() current.
  template <class OnHop>
  void feed(std::span<const float> samples, OnHop&& on_hop) {
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
  std::span<const float> window() const { return {buffer_.data() + end_ - size_, size_}; }
  long long samples_fed() const { return samples_fed_; }
  void clear() {
    std::fill(buffer_.begin(), buffer_.end(), 0.0f);
    end_ = size_;
    since_hop_ = 0;
    samples_fed_ = 0;
  }

 private:
  void push(std::span<const float> samples) {
    while (!samples.empty()) {
      if (end_ == buffer_.size()) {
        std::memmove(buffer_.data(), buffer_.data() + end_ - size_, size_ * sizeof(float));
        end_ = size_;
      }
      const std::size_t n = std::min(samples.size(), buffer_.size() - end_);
      std::memcpy(buffer_.data() + end_, samples.data(), n * sizeof(float));
      end_ += n;
      samples = samples.subspan(n);
    }
  }

  std::size_t size_;
  std::size_t hop_;
  std::vector<float> buffer_;
  std::size_t end_;  // one past the newest sample
  std::size_t since_hop_ = 0;
  long long samples_fed_ = 0;
};

}  // namespace dtmf::signal
