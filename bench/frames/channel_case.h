// A benchmark case: a name and the channel flags of `dtmfctl simulate` (protocol/sim/channel_flags.h),
// e.g. "seminar 3 m=--rir bench/rirs/seminar_room_clap.wav --distance 3 --noise pink
// --noise-dbfs -50", read through the same parser as dtmfctl's, so a case can be heard by ear
// with `dtmfctl simulate` and the same flags.
#pragma once

#include <string>

#include "sim/channel_flags.h"

namespace dtmf::bench {

// Every measured room of bench/rirs (its README.md: source, licence, RT60), by RT60: the
// benchmarks' room cases, named by file stem.
inline constexpr const char* kMeasuredRooms[] = {"studio_live_room",    "seminar_room_clap", "smoking_room",
                                                 "st_margarets_church", "st_andrews_church", "monument_chamber",
                                                 "concert_hall",        "typing_room",       "club_hall"};

struct ChannelCase {
  std::string name;
  std::string flags;
};

// "NAME=FLAGS"; throws std::invalid_argument saying how to write one.
ChannelCase parse_channel_case(const std::string& text);
// The case's flags as dtmfctl simulate reads them; throws std::invalid_argument naming the case.
sim::ChannelSetup channel_setup_of(const ChannelCase& c);

}  // namespace dtmf::bench
