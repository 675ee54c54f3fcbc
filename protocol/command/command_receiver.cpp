#include "command/command_receiver.h"

#include <cstdio>

#include "command/word_codec.h"

namespace dtmf::command {

std::string state_name(ReceiverState state) {
  switch (state) {
    case ReceiverState::Idle:
      return "idle";
    case ReceiverState::ModeSelect:
      return "mode_select";
    case ReceiverState::AwaitingParameter:
      return "awaiting_parameter";
  }
  return "unknown";
}

std::string event_kind_name(ReceiverEvent::Kind kind) {
  switch (kind) {
    case ReceiverEvent::Kind::Reset:
      return "reset";
    case ReceiverEvent::Kind::ModeSelected:
      return "mode_selected";
    case ReceiverEvent::Kind::CommandReady:
      return "command";
    case ReceiverEvent::Kind::Ignored:
      return "ignored";
  }
  return "unknown";
}

ReceiverEvent CommandReceiver::go(ReceiverEvent::Kind kind, ReceiverState next) {
  state_ = next;
  return ReceiverEvent{kind, next, pending_mode_, std::nullopt, {}};
}

ReceiverEvent CommandReceiver::ignore(std::string reason) {
  return ReceiverEvent{ReceiverEvent::Kind::Ignored, state_, pending_mode_, std::nullopt, std::move(reason)};
}

ReceiverEvent CommandReceiver::on_word(Word word) {
  word &= kWordMask;
  if (word == kResetWord) {
    pending_mode_.reset();
    return go(ReceiverEvent::Kind::Reset, ReceiverState::ModeSelect);
  }
  switch (state_) {
    case ReceiverState::Idle:
      return ignore("no RESET since the last command");
    case ReceiverState::ModeSelect: {
      const auto mode = mode_from_word(word);
      if (!mode) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "word 0x%03X names no mode", word);
        return ignore(buf);
      }
      if (*mode == Mode::ModeSelect) return ignore("already in mode_select");
      pending_mode_ = mode;
      if (*mode == Mode::Stop) {
        ReceiverEvent event = go(ReceiverEvent::Kind::CommandReady, ReceiverState::Idle);
        event.command = Stop{};
        pending_mode_.reset();
        return event;
      }
      return go(ReceiverEvent::Kind::ModeSelected, ReceiverState::AwaitingParameter);
    }
    case ReceiverState::AwaitingParameter: {
      ParameterDecode decoded = decode_parameters(*pending_mode_, word);
      if (!decoded.command) {
        // A damaged command must not half-happen: drop it and wait for the next RESET.
        ReceiverEvent event = go(ReceiverEvent::Kind::Ignored, ReceiverState::Idle);
        event.reason = decoded.error;
        pending_mode_.reset();
        return event;
      }
      ReceiverEvent event = go(ReceiverEvent::Kind::CommandReady, ReceiverState::Idle);
      event.command = std::move(decoded.command);
      pending_mode_.reset();
      return event;
    }
  }
  return ignore("unreachable state");
}

}  // namespace dtmf::command
