#include "link/transmit_plan.h"

#include "link/command_frame_path.h"
#include "link/sender_path.h"
#include "reliability/command_frame.h"
#include "signal/bin_synthesizer.h"
#include "signal/synthesizer.h"

namespace dtmf::link {

std::vector<TransmitFrame> plan_transmission(const LinkProfile& profile, const command::Command& command,
                                             std::uint8_t& next_sequence) {
  std::vector<TransmitFrame> frames;
  if (profile.frame_format == FrameFormat::Command48) {
    const PlannedCommandFrame planned = plan_command_frame(command, next_sequence);
    next_sequence = static_cast<std::uint8_t>((planned.frame.sequence + 1) & reliability::kSequenceMask);
    TransmitFrame f;
    f.bits = planned.bits;
    f.bit_count = reliability::kCommandFrameBits;
    f.sequence = planned.frame.sequence;
    const auto tones = signal::symbol_tones_hz(profile, planned.symbols);
    f.tones_hz.assign(tones.begin(), tones.end());
    f.audio = render_command_frame(profile, planned);
    f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile.sample_rate_hz;
    frames.push_back(std::move(f));
    return frames;
  }
  for (const PlannedFrame& planned : plan_command(profile, command)) {
    TransmitFrame f;
    f.word = planned.word;
    f.bits = planned.frame;
    f.bit_count = reliability::kFrameBits;
    f.tones_hz.assign(planned.tones_hz.begin(), planned.tones_hz.end());
    f.audio = signal::synthesize_chord(profile, planned.tones_hz, profile.timing.chord_ms);
    f.tone_ms = profile.timing.chord_ms;
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace dtmf::link
