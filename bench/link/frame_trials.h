// Benchmarks' view of a link: random frames, their audio, and the robot's and the sender's
// receive paths, all through link::Link (protocol/link/link.h), so no benchmark knows a
// frame format.
//
// Every frame-level benchmark (SNR sweep, distance sweep, rooms, talk-off, decoder speed,
// smoke test) asks for:
//   1. a random frame (seeded): its bits as sent and its audio (Link::random_frame);
//   2. the slot it is sent in: the frame, then the silence a sender leaves before the next;
//   3. a receiver: audio in, blocks of any size, out the frames that passed the check
//      (accepted, with their bits and when they started) and how many failed it.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include "link/link.h"

namespace dtmf::bench {

// The bits of one frame as sent or accepted (data and check bits, right-aligned).
using FrameBits = std::uint64_t;

struct Accepted {
  double start_ms;  // when it began sounding, from the receiver's first sample
  FrameBits bits;
};

class FrameReceiver {
 public:
  explicit FrameReceiver(const link::Link& link) : receiver_(link.receiver()) {}
  // Frames that passed the check within `samples` are appended to `accepted`; the ones
  // that failed it are counted (a real robot NACKs those).
  void feed(std::span<const float> samples, std::vector<Accepted>& accepted);
  std::uint64_t check_failed() const { return check_failed_; }

 private:
  std::unique_ptr<link::FrameReceiver> receiver_;
  std::uint64_t check_failed_ = 0;
};

// The sender's side: ACKs and NACKs heard.
class ReplyReceiver {
 public:
  explicit ReplyReceiver(const link::Link& link) : listener_(link.answer_listener()) {}
  void feed(std::span<const float> samples);
  std::uint64_t acks() const { return acks_; }
  std::uint64_t nacks() const { return nacks_; }

 private:
  std::unique_ptr<link::AnswerListener> listener_;
  std::uint64_t acks_ = 0, nacks_ = 0;
};

// The robot as the round trip needs it: the answer audio to every verdict it reaches.
class Responder {
 public:
  explicit Responder(const link::Link& link) : link_(link), receiver_(link.receiver()) {}
  std::vector<std::vector<float>> feed(std::span<const float> samples);

 private:
  const link::Link& link_;
  std::unique_ptr<link::FrameReceiver> receiver_;
};

class FrameTrials {
 public:
  explicit FrameTrials(const link::Link& link);

  const LinkProfile& profile() const { return link_.profile(); }
  const link::Link& link() const { return link_; }
  int data_bits() const { return data_bits_; }                  // payload bits per frame (what a command carries)
  int check_bits() const { return check_bits_; }                // bits spent on the check (CRC)
  std::size_t slot_samples() const { return slot_samples_; }    // one frame + its gap
  std::size_t sound_samples() const { return sound_samples_; }  // the non-silent part of a slot

  // Never the frame just drawn again: a sender numbers its frames, and a robot takes the same
  // frame heard twice within its retransmission time for one sound heard twice.
  link::TransmitFrame random_frame(std::mt19937_64& rng);
  // Adds the frame's audio to the start of `slot` (slot.size() >= sound_samples()).
  static void add_frame(const link::TransmitFrame& frame, std::span<float> slot);

 private:
  const link::Link& link_;
  int data_bits_ = 0;
  int check_bits_ = 0;
  std::size_t slot_samples_ = 0;
  std::size_t sound_samples_ = 0;
  std::uint64_t last_bits_ = ~std::uint64_t{0};
};

}  // namespace dtmf::bench
