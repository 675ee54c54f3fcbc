// One interface for what a link profile does, whatever its wire format: the sender's path
// (command -> frames -> audio), the robot's path (audio -> verdicts on frames -> commands)
// with its answer (ACK / NACK audio), and the sender's ear (audio -> answers).
//
// Programs and benchmarks choose a link by profile name (link_by_name) and use only this:
// none of them asks which wire format a profile has. Each format keeps its own paths behind
// it (the seed's words: sender_path.h, receiver_path.h; the fast profile's frames:
// command_frame_path.h), so adding or changing a profile touches protocol/ and the docs only.
// Pure: no device, no clock; the audio is rendered, not played.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "command/command.h"
#include "link/transmit_plan.h"
#include "profile/link_profile.h"

namespace dtmf::link {

// A frame the robot reached a verdict on: intact (answer ACK) or not (answer NACK).
struct Reception {
  double start_ms = 0;     // when the frame began sounding (within an analysis hop)
  double heard_ms = 0;     // when the verdict was reached: the robot's decision time
  std::uint64_t bits = 0;  // the frame as accepted, or as first read when broken
  int bit_count = 0;
  int check_bit_count = 0;  // the low bits that are the check
  bool intact = false;
  std::optional<std::uint8_t> sequence;     // formats whose ACK names the frame
  std::optional<command::Word> word;        // word formats: the intact frame's word
  std::optional<command::Command> command;  // the command to execute now: completed by this
                                            // word, or carried by a new frame
  // What the frame did: "reset", "mode_selected", "command", "ignored" (word formats),
  // "command", "repeat" (answered, not executed again), "refused" (intact but no command
  // a sender makes), or "" for a broken frame.
  std::string event;
  std::string state_after;       // word formats: the command state machine afterwards
  std::string detail;            // for people: what it did, or why it was refused
  std::vector<double> tones_hz;  // the tones that carry `bits`, in order
};

// An ACK or a NACK the sender heard.
struct Answer {
  bool ack = false;
  std::optional<std::uint8_t> sequence;  // named by the ACK, in formats that name frames
  double heard_ms = 0;
};

// The robot's receive path: audio in, verdicts out. Times are milliseconds since the first
// sample fed. The returned span is valid until the next call.
class FrameReceiver {
 public:
  virtual ~FrameReceiver() = default;
  virtual std::span<const Reception> feed(std::span<const float> samples) = 0;
};

// The sender's ear: audio in, answers out.
class AnswerListener {
 public:
  virtual ~AnswerListener() = default;
  virtual std::span<const Answer> feed(std::span<const float> samples) = 0;
};

class Link {
 public:
  explicit Link(const LinkProfile& profile) : profile_(profile) {}
  virtual ~Link() = default;
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  const LinkProfile& profile() const { return profile_; }
  const std::string& name() const { return profile_.name; }

  // --- the sender ---
  // The frames of `command` in transmission order, with their audio. Formats that number
  // frames take `next_sequence` (or the next usable number) and advance it past the number
  // used. Throws command::ParameterError for a bad parameter.
  virtual std::vector<TransmitFrame> plan(const command::Command& command, std::uint8_t& next_sequence) const = 0;
  // How many frames `command` takes.
  std::size_t frame_count(const command::Command& command) const;
  // One frame carrying a raw word, for formats whose frames are words (dtmfctl encode
  // --word); nothing for formats that only send whole commands.
  virtual std::optional<TransmitFrame> plan_word(std::uint32_t word) const;
  // `command` as the robot will execute it: its parameters through the format's fields.
  virtual command::Command as_received(const command::Command& command) const = 0;
  // Payload bits a command's frames carry, the check excluded (for throughput figures).
  virtual int payload_bits(const command::Command& command) const = 0;
  // A frame of random content that a sender could send (seeded), for benchmarks: every
  // value its fields can take, not just the commands of a test sequence.
  virtual TransmitFrame random_frame(std::uint64_t seed) const = 0;
  // Offline (dtmfctl encode --wav): where frame `index` of a recording starts, and the
  // frames laid out so, each followed by the silence a sender leaves for its answer.
  virtual double frame_start_ms(std::size_t index) const = 0;
  std::vector<float> render(std::span<const TransmitFrame> frames) const;

  // --- the robot ---
  virtual std::unique_ptr<FrameReceiver> receiver() const = 0;
  // The answer to `reception`: ACK (naming the frame where the format does) or NACK.
  virtual std::vector<float> answer_audio(const Reception& reception) const = 0;
  // The block a live receiver should be fed in (its analysis hop).
  virtual int receiver_block_samples() const = 0;

  // --- the sender's ear ---
  virtual std::unique_ptr<AnswerListener> answer_listener() const = 0;
  // The block to read the microphone in, so an answer is heard as soon as it is complete.
  virtual int answer_block_samples() const = 0;
  // Whether `answer` is an answer to `frame` (a named ACK must name it).
  virtual bool answers(const Answer& answer, const TransmitFrame& frame) const = 0;

 private:
  const LinkProfile& profile_;
};

// The link of every profile in all_profiles(), in the same order.
const std::vector<const Link*>& all_links();
const Link& link_for(const LinkProfile& profile);
// Throws std::invalid_argument naming the known profiles.
const Link& link_by_name(std::string_view name);

}  // namespace dtmf::link
