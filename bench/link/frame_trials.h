// Benchmarks' adapter to the link's frame format: the ONE file that knows what a frame is.
//
// Every frame-level benchmark (SNR sweep, distance sweep, talk-off, smoke test) asks this
// adapter for three things and nothing else:
//   1. a random frame (seeded) and its bits as sent;
//   2. the frame's audio, rendered into the start of its slot (chord, then silence);
//   3. a receiver: audio in, blocks of any size, out the frames that passed the check
//      (accepted, with their bits and when they started) and how many failed it.
// Word16 (profile `seed`): 12 data bits + CRC-4, one four-tone chord per frame, built on
// link::plan_word, link::render_frames and link::ReceiverPath. Command48 (profile `fast`):
// a 4-bit sequence number, a 28-bit command payload and CRC-16 in two chords, built on
// link::plan_command_frame, link::render_command_frame and link::CommandFramePath; its
// random frames are random valid commands, since the robot refuses payloads no sender makes.
#pragma once

#include <cstdint>
#include <map>
#include <random>
#include <span>
#include <vector>

#include <memory>
#include <optional>

#include "command/command.h"
#include "link/command_frame_path.h"
#include "link/receiver_path.h"
#include "profile/link_profile.h"
#include "signal/bin_reply_listener.h"
#include "signal/tone_listener.h"

namespace dtmf::bench {

// The bits of one frame as sent or accepted (data and check bits, right-aligned).
using FrameBits = std::uint64_t;

struct Accepted {
  double start_ms;  // when it began sounding, from the receiver's first sample
  FrameBits bits;
};

class FrameReceiver {
 public:
  explicit FrameReceiver(const LinkProfile& profile);
  // Frames that passed the check within `samples` are appended to `accepted`; the ones
  // that failed it are counted (a real robot NACKs those).
  void feed(std::span<const float> samples, std::vector<Accepted>& accepted);
  std::uint64_t check_failed() const { return check_failed_; }

 private:
  std::unique_ptr<link::ReceiverPath> words_;       // Word16
  std::unique_ptr<link::CommandFramePath> commands_;  // Command48
  std::uint64_t check_failed_ = 0;
};

// The sender's side: ACK and NACK replies heard (signal::reply_listener for this format).
class ReplyReceiver {
 public:
  explicit ReplyReceiver(const LinkProfile& profile);
  void feed(std::span<const float> samples);
  std::uint64_t acks() const { return acks_; }
  std::uint64_t nacks() const { return nacks_; }

 private:
  std::unique_ptr<signal::ToneListener> replies_;         // Word16
  std::unique_ptr<signal::BinReplyListener> named_;       // Command48
  std::uint64_t acks_ = 0, nacks_ = 0;
};

// The round trip's roles (bench/link/round_trip.cpp): what the sender plays for a command,
// how the robot answers what it hears, and what the sender hears of the answers.
struct Transmission {
  std::vector<float> audio;               // one frame, ready to play
  std::optional<std::uint8_t> sequence;   // the number an ACK must name (Command48)
};
// The frames of `command` in order; `next_sequence` numbers Command48 frames.
std::vector<Transmission> command_transmissions(const LinkProfile& profile, const command::Command& command,
                                                std::uint8_t& next_sequence);
// Payload bits of `command` as sent (Word16: 12 per word, CRC excluded; Command48: 28).
int command_payload_bits(const LinkProfile& profile, const command::Command& command);

class Responder {
 public:
  explicit Responder(const LinkProfile& profile);
  // The answers (ACK / NACK audio) to every verdict reached within `samples`.
  std::vector<std::vector<float>> feed(std::span<const float> samples);

 private:
  const LinkProfile& profile_;
  std::unique_ptr<link::ReceiverPath> words_;
  std::unique_ptr<link::CommandFramePath> commands_;
};

struct Answer {
  bool ack = false;
  std::optional<std::uint8_t> sequence;  // named by a Command48 ACK
};

class AnswerListener {
 public:
  explicit AnswerListener(const LinkProfile& profile);
  std::vector<Answer> feed(std::span<const float> samples);

 private:
  std::unique_ptr<signal::ToneListener> replies_;
  std::unique_ptr<signal::BinReplyListener> named_;
};

// Payload bits one frame carries (its data bits, the check excluded) under `profile`'s frame
// format; the end-to-end benchmark counts a command's payload with it.
int frame_data_bits(const LinkProfile& profile);

class FrameTrials {
 public:
  explicit FrameTrials(const LinkProfile& profile);

  const LinkProfile& profile() const { return profile_; }
  int data_bits() const;   // payload bits per frame (what a command carries)
  int check_bits() const;  // bits spent on the check (CRC)
  std::size_t slot_samples() const { return slot_samples_; }    // one frame + its gap
  std::size_t sound_samples() const { return sound_samples_; }  // the non-silent part of a slot

  FrameBits random_frame(std::mt19937_64& rng) const;
  // Adds the frame's audio to slot[0, sound_samples()); slot.size() >= sound_samples().
  // Bit-identical to link::render_frames (checked once at construction).
  void add_frame(FrameBits bits, std::span<float> slot);

 private:
  const std::vector<float>& tone(double frequency_hz);

  const LinkProfile& profile_;
  std::size_t slot_samples_;
  std::size_t sound_samples_;
  // A chord is a sum of tones that each start at phase 0; rendering each tone once and
  // summing in the synthesizer's order gives the same floats at a fraction of the cost.
  std::map<double, std::vector<float>> tones_;
};

}  // namespace dtmf::bench
