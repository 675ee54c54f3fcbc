// The seed profile's sender path through the layers: command -> words -> frames -> tones -> audio.
//
// Each layer is called in turn; this file only strings them together and lays the chords
// out in time (chord_ms of tone, gap_ms of silence) for offline use, such as
// `dtmfctl encode --wav`. The live transmitter (server/) paces frames by their answers.
#pragma once

#include <vector>

#include "command/command.h"
#include "profile/link_profile.h"
#include "reliability/crc4.h"
#include "signal/tone_plan.h"

namespace dtmf::link {

struct SeedPlannedFrame {
  command::Word word;
  reliability::SeedFrame frame;
  signal::Chord tones_hz;
};

SeedPlannedFrame plan_word(const LinkProfile& profile, command::Word word);

// The frames of `command` in transmission order; throws command::ParameterError.
std::vector<SeedPlannedFrame> plan_command(const LinkProfile& profile, const command::Command& command);

// Where each frame's chord starts in a rendered recording.
double frame_start_ms(const LinkProfile& profile, std::size_t index);

}  // namespace dtmf::link
