#include "link/seed_receiver_path.h"

namespace dtmf::link {

SeedReceiverPath::SeedReceiverPath(const LinkProfile& profile, bool execute_words)
    : listener_(signal::chord_listener(profile)), execute_words_(execute_words) {}

std::span<const SeedReceivedFrame> SeedReceiverPath::feed(std::span<const float> samples) {
  received_.clear();
  for (const signal::Heard& heard : listener_.feed(samples)) {
    const auto frame = static_cast<reliability::SeedFrame>(heard.symbol);
    SeedReceivedFrame received{heard.start_ms, heard.heard_ms, frame, reliability::word_frame_intact(frame),
                               std::nullopt};
    if (received.crc_ok && execute_words_) received.event = commands_.on_word(reliability::word_frame_word(frame));
    received_.push_back(std::move(received));
  }
  return received_;
}

}  // namespace dtmf::link
