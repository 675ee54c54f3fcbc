// A simulated loudspeaker for the benchmarks that run in simulated time: it plays the buffers
// queued to it one after another, block by block, and silence when it has none.
#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <span>
#include <utility>
#include <vector>

namespace dtmf::bench {

class Speaker {
 public:
  void queue(std::vector<float> audio) { queue_.push_back(std::move(audio)); }
  bool idle() const { return queue_.empty(); }
  void next_block(std::span<float> out) {
    std::fill(out.begin(), out.end(), 0.0f);
    std::size_t at = 0;
    while (at < out.size() && !queue_.empty()) {
      const auto& front = queue_.front();
      const std::size_t n = std::min(out.size() - at, front.size() - position_);
      std::copy_n(front.begin() + static_cast<long>(position_), n, out.begin() + static_cast<long>(at));
      at += n;
      position_ += n;
      if (position_ == front.size()) {
        queue_.pop_front();
        position_ = 0;
      }
    }
  }

 private:
  std::deque<std::vector<float>> queue_;
  std::size_t position_ = 0;
};

}  // namespace dtmf::bench
