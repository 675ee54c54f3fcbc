// Command abstraction layer: a visitor made of one lambda per alternative, for std::visit over
// Command. It has no catch-all: a new alternative of Command is a compile error in every
// visitor that does not name it, instead of going out as whatever a default did (issue 23's
// review found a new command would have been sent as STOP or TURN). Header-only.
#pragma once

namespace dtmf::command {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace dtmf::command
