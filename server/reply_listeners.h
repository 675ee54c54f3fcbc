// The sender's ears: every profile's reply detector on the same microphone audio.
//
//   samples -> Word16 profiles: ToneListener (ACK / NACK chords, seed Fig. 8)
//           -> Command48 profiles: BinReplyListener (ACK naming a sequence number, or NACK)
//           -> one list of answers, each tagged with the profile that heard it
//
// The transmitter waits for an answer of the profile of the frame on air, so each profile
// may send in its own way over one loudspeaker and one microphone. Times are milliseconds
// of audio since the first sample fed.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "profile/link_profile.h"
#include "signal/bin_reply_listener.h"
#include "signal/tone_listener.h"

namespace dtmf::server {

struct HeardAnswer {
  const LinkProfile* profile = nullptr;
  bool ack = false;
  std::optional<std::uint8_t> sequence;  // Command48 ACKs name the frame they answer
  double heard_ms = 0;
};

class ReplyListeners {
 public:
  // All profiles must share one sample rate (they share one microphone).
  explicit ReplyListeners(std::span<const LinkProfile* const> profiles);
  std::vector<HeardAnswer> feed(std::span<const float> samples);
  // The block to read the microphone in: every listener's hop divides into it, so an answer
  // is heard as soon as its last window is in (the fast reply's hop is 4 ms).
  int block_samples() const { return block_samples_; }

 private:
  struct ChordEar {  // the listener is built in place: it owns an FFT plan and cannot move
    explicit ChordEar(const LinkProfile& p) : profile(&p), listener(signal::reply_listener(p)) {}
    const LinkProfile* profile;
    signal::ToneListener listener;
  };
  int block_samples_ = 0;
  std::vector<std::unique_ptr<ChordEar>> chord_listeners_;
  std::vector<std::pair<const LinkProfile*, std::unique_ptr<signal::BinReplyListener>>> named_listeners_;
};

}  // namespace dtmf::server
