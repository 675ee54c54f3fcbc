// Signal layer: the latest N samples of a stream as one contiguous span.
//
// Samples are appended to a buffer of 5N; only when it is full are the latest N moved back
// to its start. The window thus costs one copy of each sample plus one move of N samples
// every 4N samples, instead of a move of N samples at every analysis hop.
// Nothing is allocated after construction.
#pragma once

#include <algorithm>
#include <cstring>
#include <span>
#include <vector>

namespace dtmf::signal {

class SlidingWindow {
 public:
  explicit SlidingWindow(std::size_t size) : size_(size), buffer_(5 * size, 0.0f), end_(size) {}

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
  // The latest size() samples, oldest first; valid until the next push().
  std::span<const float> window() const { return {buffer_.data() + end_ - size_, size_}; }
  std::size_t size() const { return size_; }
  void clear() {
    std::fill(buffer_.begin(), buffer_.end(), 0.0f);
    end_ = size_;
  }

 private:
  std::size_t size_;
  std::vector<float> buffer_;
  std::size_t end_;  // one past the newest sample
};

}  // namespace dtmf::signal
