#include "link/seed_sender_path.h"

#include "command/word_codec.h"
#include "signal/synthesizer.h"

namespace dtmf::link {

SeedPlannedFrame plan_word(const LinkProfile& profile, command::Word word) {
  const reliability::SeedFrame frame = reliability::word_frame_make(word & command::kWordMask);
  return SeedPlannedFrame{static_cast<command::Word>(word & command::kWordMask), frame,
                          signal::chord_for(profile.words().tones, frame)};
}

std::vector<SeedPlannedFrame> plan_command(const LinkProfile& profile, const command::Command& command) {
  std::vector<SeedPlannedFrame> frames;
  for (command::Word word : command::encode(command)) frames.push_back(plan_word(profile, word));
  return frames;
}

double frame_start_ms(const LinkProfile& profile, std::size_t index) {
  return static_cast<double>(index) * (profile.timing.chord_ms + profile.timing.gap_ms);
}

}  // namespace dtmf::link
