// The seed profile's robot path through the layers: audio -> spectrum -> chord -> frame -> word -> command.
//
// Audio goes to the signal layer's chord listener (debounced chords), each chord is checked
// by the reliability layer (CRC-4), and the words of intact frames drive the command layer's
// state machine. Every heard frame is reported, intact or not, so the caller can answer it
// with ACK or NACK and log it; what the word did to the command state rides along.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "command/command_receiver.h"
#include "profile/link_profile.h"
#include "reliability/crc4.h"
#include "signal/tone_listener.h"

namespace dtmf::link {

struct SeedReceivedFrame {
  double start_ms;  // when the chord began sounding (within one analysis hop)
  double heard_ms;  // when the debouncer passed it
  reliability::SeedFrame frame;
  bool crc_ok;
  std::optional<command::ReceiverEvent> event;  // for intact frames only
};

class SeedReceiverPath {
 public:
  // `execute_words` false: intact frames are reported but never reach the state machine (a
  // robot with a key refuses the seed's unauthenticated words).
  explicit SeedReceiverPath(const LinkProfile& profile, bool execute_words = true);

  // Frames heard within `samples`; valid until the next call.
  std::span<const SeedReceivedFrame> feed(std::span<const float> samples);

  const command::CommandReceiver& commands() const { return commands_; }
  const signal::ToneListener& listener() const { return listener_; }

 private:
  signal::ToneListener listener_;
  bool execute_words_;
  command::CommandReceiver commands_;
  std::vector<SeedReceivedFrame> received_;
};

}  // namespace dtmf::link
