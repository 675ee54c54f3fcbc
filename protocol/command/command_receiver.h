// Command abstraction layer: the robot's state machine that turns words into commands.
//
//   Idle --RESET--> ModeSelect --mode word--> AwaitingParameter --parameter--> Idle (command)
//                   ModeSelect --STOP word--> Idle (stop command)
//
// RESET is honoured in every state; any other word is read according to the state. A word
// that fits no transition is ignored and the event says why. Pure logic: no I/O, no clock.
#pragma once

#include <optional>
#include <string>

#include "command/command.h"

namespace dtmf::command {

enum class ReceiverState { Idle, ModeSelect, AwaitingParameter };

std::string state_name(ReceiverState state);

struct ReceiverEvent {
  enum class Kind {
    Reset,         // RESET word: now in MODE_SELECT
    ModeSelected,  // a mode word: now waiting for its parameter word
    CommandReady,  // a complete command is ready to execute
    Ignored,       // the word fit no transition; `reason` says why
  };
  Kind kind;
  ReceiverState state_after;
  std::optional<Mode> mode;
  std::optional<command::Command> command;
  std::string reason;
};

std::string event_kind_name(ReceiverEvent::Kind kind);

class CommandReceiver {
 public:
  ReceiverEvent on_word(Word word);
  ReceiverState state() const { return state_; }
  std::optional<Mode> pending_mode() const { return pending_mode_; }

 private:
  ReceiverEvent go(ReceiverEvent::Kind kind, ReceiverState next);
  ReceiverEvent ignore(std::string reason);

  ReceiverState state_ = ReceiverState::Idle;
  std::optional<Mode> pending_mode_;
};

}  // namespace dtmf::command
