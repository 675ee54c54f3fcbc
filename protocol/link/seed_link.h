// The `seed` profile's link: the report's words, CRC-4 frames and four-tone chords behind
// the Link interface (link.h). An ACK names no frame, so any ACK answers the frame on air.
// Its 16-bit frames cannot carry a MAC: a sender with a key sends them unauthenticated, and a
// robot with a key refuses them unless told to let unauthenticated frames in.
#pragma once

#include "link/link.h"
#include "link/seed_sender_path.h"

namespace dtmf::link {

class SeedLink final : public Link {
 public:
  using Link::Link;
  std::vector<TransmitFrame> plan(const command::Command& command) override;
  std::size_t frame_count(const command::Command& command) const override;
  bool can_authenticate() const override { return false; }
  bool addresses_robots() const override { return false; }
  std::optional<TransmitFrame> plan_payload_word(std::uint32_t word) const override;
  command::Command as_received(const command::Command& command) const override;
  int payload_bits(const command::Command& command) const override;
  TransmitFrame random_frame(std::uint64_t seed) override;
  double frame_start_ms(std::size_t index) const override;
  std::unique_ptr<FrameReceiver> receiver() const override;
  std::vector<float> answer_audio(const Reception& reception) const override;
  int receiver_block_samples() const override;
  std::unique_ptr<AnswerListener> answer_listener() const override;
  int answer_block_samples() const override;
  bool answers(const Answer& answer, const TransmitFrame& frame) const override;

  // A planned frame as the sender sends it: bits, tones and the chord's audio. Public for
  // tests that send a frame no sender plans (a word or tones corrupted on purpose) and lay
  // it out with render(), the one renderer.
  TransmitFrame transmit_frame(const SeedPlannedFrame& planned) const;
};

}  // namespace dtmf::link
