// The `fast` profile's link: a whole command per numbered frame behind the Link interface
// (link.h). Without a key, a 50-bit frame of two chords, its ACK naming the frame's sequence
// number; with one, an 80-bit frame of three chords carrying a freshness counter and a MAC,
// its ACK a tag only the key makes for that frame (docs/protocol.md §10, docs/security.md).
#pragma once

#include "link/link.h"

namespace dtmf::link {

class FastLink final : public Link {
 public:
  FastLink(const LinkProfile& profile, LinkOptions options);
  std::vector<TransmitFrame> plan(const command::Command& command) override;
  std::size_t frame_count(const command::Command& command) const override;
  bool can_authenticate() const override { return true; }
  bool addresses_robots() const override { return true; }
  command::Command as_received(const command::Command& command) const override;
  int payload_bits(const command::Command& command) const override;
  TransmitFrame random_frame(std::uint64_t seed) override;
  double frame_start_ms(std::size_t index) const override;
  void confirmed(const TransmitFrame& frame) override;
  bool renews_jointly() const override { return true; }
  RenewalRecord* renewal_record() override { return &renewal_; }
  std::unique_ptr<FrameReceiver> receiver() const override;
  std::vector<float> answer_audio(const Reception& reception) const override;
  int receiver_block_samples() const override;
  std::unique_ptr<AnswerListener> answer_listener() const override;
  int answer_block_samples() const override;
  bool answers(const Answer& answer, const TransmitFrame& frame) const override;

 private:
  TransmitFrame plain_frame(std::uint32_t payload);
  TransmitFrame sealed_frame(std::uint32_t payload, bool synchronisation, std::uint64_t counter) const;
  // A stop for every robot: the profile's broadcast copies, sealed under the room key (this
  // link's key) with the whole counter, or plain.
  std::vector<TransmitFrame> broadcast_frames(std::uint32_t payload);

  std::uint8_t next_sequence_;
  // The velocity a joint renewal renews, and the renewals' numbers (renewal_planner.h).
  RenewalRecord renewal_;
};

}  // namespace dtmf::link
