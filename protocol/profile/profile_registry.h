// Profiles beyond the built-in seed and fast: a deployment's own plan, or a test's. A
// registered profile is listed by all_profiles() and found by profile_by_name() like the
// built-in ones, so the programs take it by name with no change of theirs: they choose a
// profile by name and never look at its format (only protocol/link does, to pick the link
// that implements the plan). Register at start-up, before any thread reads the list.
#pragma once

#include "profile/link_profile.h"

namespace dtmf {

// Adds `profile` to the known ones and returns it (its address stays valid for the program's
// life). std::invalid_argument if its name is empty or taken.
const LinkProfile& register_profile(LinkProfile profile);

}  // namespace dtmf
