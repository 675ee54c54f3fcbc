// The `fast` profile's link: a whole command per numbered frame behind the Link interface
// (link.h). Its ACK names the frame's sequence number, and only that ACK answers the frame.
#pragma once

#include "link/link.h"

namespace dtmf::link {

class FastLink final : public Link {
 public:
  using Link::Link;
  std::vector<TransmitFrame> plan(const command::Command& command, std::uint8_t& next_sequence) const override;
  command::Command as_received(const command::Command& command) const override;
  int payload_bits(const command::Command& command) const override;
  TransmitFrame random_frame(std::uint64_t seed) const override;
  double frame_start_ms(std::size_t index) const override;
  std::unique_ptr<FrameReceiver> receiver() const override;
  std::vector<float> answer_audio(const Reception& reception) const override;
  int receiver_block_samples() const override;
  std::unique_ptr<AnswerListener> answer_listener() const override;
  int answer_block_samples() const override;
  bool answers(const Answer& answer, const TransmitFrame& frame) const override;
};

}  // namespace dtmf::link
