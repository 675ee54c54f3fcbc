// Benchmarks' view of a link: random frames, their audio, and the robot's and the sender's
// receive paths, all through link::Link (protocol/link/link.h), so no benchmark knows a
// frame format. With a key, the frames are authenticated: a sender's link numbers them
// with a fresh counter, and the robot's link, sharing the key, starts in step with it.
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
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "link/answer_wait.h"
#include "link/link.h"
#include "security/counter_store.h"

namespace dtmf::bench {

// The bits of one frame as sent or accepted (data and check bits, right-aligned).
using FrameBits = reliability::FrameBits;

struct Accepted {
  double start_ms;  // when it began sounding, from the receiver's first sample
  FrameBits bits;
};

class FrameReceiver {
 public:
  explicit FrameReceiver(const link::Link& link) : receiver_(link.receiver()) {}
  // Frames the robot takes (passed the check, and with a key its MAC) within `samples` are
  // appended to `accepted`; the ones that failed the check, or were refused, are counted (a
  // real robot NACKs those).
  void feed(std::span<const float> samples, std::vector<Accepted>& accepted);
  std::uint64_t check_failed() const { return check_failed_; }
  std::uint64_t refused() const { return refused_; }

 private:
  std::unique_ptr<link::FrameReceiver> receiver_;
  std::uint64_t check_failed_ = 0;
  std::uint64_t refused_ = 0;
};

// The sender's side: ACKs and NACKs heard, and how many of the ACKs would have confirmed a
// frame the sender was waiting for. The sender is taken to wait all the time: for a new
// random frame of its link every ack_timeout_ms (as a sender retrying unanswered frames).
class ReplyReceiver {
 public:
  explicit ReplyReceiver(link::Link& sender);
  void feed(std::span<const float> samples);
  std::uint64_t acks() const { return acks_; }
  std::uint64_t nacks() const { return nacks_; }
  std::uint64_t confirmations() const { return confirmations_; }

 private:
  link::Link& sender_;
  std::unique_ptr<link::AnswerListener> listener_;
  link::TransmitFrame waiting_for_;
  std::optional<link::AnswerWait> wait_;  // for waiting_for_
  double waiting_until_ms_ = 0;
  double audio_ms_ = 0;
  std::uint64_t next_seed_ = 1;
  std::uint64_t acks_ = 0, nacks_ = 0, confirmations_ = 0;
};

// The robot as the round trip needs it: the answer audio to every verdict it reaches.
class Responder {
 public:
  explicit Responder(const link::Link& link) : link_(link), receiver_(link.receiver()) {}
  // The answer audio to every verdict within `samples` (refusals and broken frames: NACK).
  std::vector<std::vector<float>> feed(std::span<const float> samples);

 private:
  const link::Link& link_;
  std::unique_ptr<link::FrameReceiver> receiver_;
};

class FrameTrials {
 public:
  // A sender's and a robot's link of `profile`, with `key` (none: unauthenticated).
  explicit FrameTrials(const LinkProfile& profile, std::shared_ptr<const security::LinkKey> key = nullptr);

  const LinkProfile& profile() const { return link_->profile(); }
  const link::Link& link() const { return *link_; }  // the sender's
  const link::Link& robot() const { return *robot_; }
  int data_bits() const { return data_bits_; }                  // payload bits per frame (what a command carries)
  int check_bits() const { return check_bits_; }                // bits spent on the check (CRC)
  std::size_t slot_samples() const { return slot_samples_; }    // one frame + its gap
  std::size_t sound_samples() const { return sound_samples_; }  // the non-silent part of a slot

  // Never the frame just drawn again: a sender numbers its frames, and a robot takes the same
  // frame heard twice within its retransmission time for one sound heard twice.
  link::TransmitFrame random_frame(std::mt19937_64& rng);
  // The shortest command's frame (a Stop), numbered as plan() numbers it.
  link::TransmitFrame stop_frame();
  // Adds the frame's audio to the start of `slot` (slot.size() >= sound_samples()).
  static void add_frame(const link::TransmitFrame& frame, std::span<float> slot);

 private:
  std::unique_ptr<link::Link> link_;
  std::unique_ptr<link::Link> robot_;
  int data_bits_ = 0;
  int check_bits_ = 0;
  std::size_t slot_samples_ = 0;
  std::size_t sound_samples_ = 0;
  std::optional<FrameBits> last_bits_;
};

}  // namespace dtmf::bench
