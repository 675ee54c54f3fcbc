// A frame as the sender sends, paces and logs it, whatever the profile's format: its bits,
// the tones that carry them, and the audio the loudspeaker plays. Links (link.h) plan them.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "command/command.h"
#include "reliability/frame_bits.h"
#include "reliability/tag_chord.h"

namespace dtmf::link {

struct TransmitFrame {
  std::optional<command::Word> word;          // seed words: the 12-bit word the frame carries
  reliability::FrameBits bits;                // the frame as sent, check included
  int bit_count = 0;                          // 16 (seed), 50 (fast), 80 (fast, authenticated)
  int check_bit_count = 0;                    // the low bits that are the check (CRC)
  std::optional<std::uint8_t> sequence;       // numbered frames: the number its ACK must name
  std::uint8_t address = 0;                   // addressed frames: the robot it is for, whose answer alone counts
  bool authenticated = false;                 // carries a MAC (sealed frames)
  bool synchronisation = false;               // a counter synchronisation, no command
  bool broadcast = false;                     // for every robot (a stop), which none answers
  bool renewal = false;                       // a joint renewal of several robots' velocities, which none answers
  std::optional<std::uint64_t> counter;       // authenticated frames: the freshness counter
  reliability::TagChordSymbols answer_tag{};  // authenticated frames: the tag its ACK must spell
  reliability::BandValueSet sent_tones{};     // ... and the tones the frame sent in each band, set aside there
  int answer_lane = 0;                        // where an untagged ACK sounds (fast: the reply lane, signal/hop_reply.h)
  std::vector<double> tones_hz;               // every tone, chord after chord, in order
  std::vector<float> audio;                   // what the loudspeaker plays, tone_ms long
  double tone_ms = 0;                         // sound on air
  // How long after the frame's start the sender may begin its next frame: the frame, the
  // profile's gap after it, and the answer it asks for where that sounds in the frame bands.
  // A tag chord does (reliability/tag_chord.h), and a next frame begun under it would be read
  // by the robot through its own chord's cut-off, 20 dB louder at its microphone. Set when the
  // frame is planned, so that every sender (the server, a benchmark) paces alike.
  double next_frame_after_ms = 0;
};

}  // namespace dtmf::link
