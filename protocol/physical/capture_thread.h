// Physical layer: a live microphone drained by a thread of its own that only copies, its
// samples handed to the decoder through a buffer.
//
// Why a thread of its own: decoding is the heaviest work on either side (an FFT every few
// milliseconds), and the device must be drained in time whatever the decoder is doing. Why it
// is not real-time (physical/realtime_priority.h): PortAudio's ALSA read polls in a loop until
// the sound library's thread (ALSA's PulseAudio plugin, SCHED_FIFO 4) has moved the samples;
// a reader at that same rank kept that thread off the CPU, and with 20 agents on 2 cores two
// readers spun at 94 % CPU while every other process, sound server included, starved for ten
// minutes. So it runs at a raised nice level, below the thread it waits for, and the decoder
// that reads from it at normal priority.
//
// What the decoder has not yet taken waits here, up to `capacity_ms`; beyond that the newest
// samples are dropped, counted and reported, as a device's own overflow would drop them.
// The end of the inner source (0) and its failure (AudioError) reach the reader after the
// samples read before them.
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "physical/audio_io.h"

namespace dtmf::physical {

// How long one read of the device is: the delay the hand-over adds at most.
inline constexpr double kCaptureChunkMs = 10;
// Audio a decoder may fall behind by before samples are lost: far longer than any stall
// a loaded machine showed (a few hundred ms), short enough to hold (480 000 floats, 1.9 MB).
inline constexpr double kDefaultCaptureCapacityMs = 10'000;

class CaptureThread : public AudioSource {
 public:
  explicit CaptureThread(std::unique_ptr<AudioSource> device, double capacity_ms = kDefaultCaptureCapacityMs);
  ~CaptureThread() override;
  CaptureThread(const CaptureThread&) = delete;
  CaptureThread& operator=(const CaptureThread&) = delete;

  // Blocks until out.size() samples are captured; fewer (then 0) once the device ended.
  // Throws the device's AudioError once every sample read before it was taken.
  std::size_t read(std::span<float> out) override;
  // The device's own queue (as of its last read) plus what waits here.
  double queued_ms() const override;
  int sample_rate_hz() const override { return rate_hz_; }
  std::string describe() const override { return description_; }

  // Samples the decoder fell too far behind to keep.
  long long dropped_samples() const;

 private:
  void capture();

  std::unique_ptr<AudioSource> device_;
  const int rate_hz_;
  const std::string description_;
  const std::size_t capacity_samples_;

  mutable std::mutex mutex_;
  std::condition_variable captured_;
  std::vector<float> ring_;  // capacity_samples_ long; [head_, head_ + size_) modulo
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  long long dropped_ = 0;
  long long drops_ = 0;          // chunks dropped, to warn at the first and every 100th
  double device_queued_ms_ = 0;  // the device's queue after the last read
  bool ended_ = false;
  std::string failure_;  // the device's error, once it failed
  bool stopping_ = false;
  std::thread thread_;  // last: starts once the rest is built
};

}  // namespace dtmf::physical
