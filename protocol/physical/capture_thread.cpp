#include "physical/capture_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "physical/realtime_priority.h"

namespace dtmf::physical {

namespace {
std::size_t samples_in(double ms, int rate_hz) { return static_cast<std::size_t>(std::ceil(ms * rate_hz / 1000.0)); }
}  // namespace

CaptureThread::CaptureThread(std::unique_ptr<AudioSource> device, double capacity_ms)
    : device_(std::move(device)),
      rate_hz_(device_->sample_rate_hz()),
      description_(device_->describe()),
      capacity_samples_(std::max(samples_in(capacity_ms, rate_hz_), 2 * samples_in(kCaptureChunkMs, rate_hz_))),
      ring_(capacity_samples_),
      thread_([this] { capture(); }) {}

CaptureThread::~CaptureThread() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  thread_.join();
}

void CaptureThread::capture() {
  std::string how;
  raise_capture_thread_priority(&how);
  spdlog::info("reading {} in a thread of its own ({}); decoding at normal priority", description_, how);
  std::vector<float> chunk(samples_in(kCaptureChunkMs, rate_hz_));
  while (true) {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
    }
    std::size_t got = 0;
    std::string failure;
    try {
      got = device_->read(chunk);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    // Asked here, in the one thread that reads the device: PortAudio wants one thread per stream.
    const double device_queued_ms = got == 0 ? 0 : device_->queued_ms();
    std::lock_guard lock(mutex_);
    device_queued_ms_ = device_queued_ms;
    if (got == 0) {
      ended_ = true;
      failure_ = failure;
      captured_.notify_all();
      return;
    }
    if (capacity_samples_ - size_ < got) {
      // The decoder is seconds behind: lose the newest, as an overflowing device would.
      dropped_ += static_cast<long long>(got);
      if (drops_++ % 100 == 0) {
        spdlog::warn("the decoder is {:.1f} s behind {}: {} samples lost so far; the machine is too busy",
                     static_cast<double>(size_) / rate_hz_, description_, dropped_);
      }
      continue;
    }
    for (std::size_t i = 0; i < got; ++i) ring_[(head_ + size_ + i) % capacity_samples_] = chunk[i];
    size_ += got;
    captured_.notify_all();
  }
}

std::size_t CaptureThread::read(std::span<float> out) {
  std::unique_lock lock(mutex_);
  captured_.wait(lock, [&] { return size_ >= out.size() || ended_; });
  const std::size_t n = std::min(out.size(), size_);
  if (n == 0 && !failure_.empty()) throw AudioError(failure_);
  for (std::size_t i = 0; i < n; ++i) out[i] = ring_[(head_ + i) % capacity_samples_];
  head_ = (head_ + n) % capacity_samples_;
  size_ -= n;
  return n;
}

double CaptureThread::queued_ms() const {
  std::lock_guard lock(mutex_);
  return device_queued_ms_ + 1000.0 * static_cast<double>(size_) / rate_hz_;
}

long long CaptureThread::dropped_samples() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace dtmf::physical
