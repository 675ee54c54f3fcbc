// Command abstraction layer: the robot's word-by-word state machine.
#include <gtest/gtest.h>

#include "command/command_receiver.h"
#include "command/word_codec.h"

using namespace dtmf::command;
using Kind = ReceiverEvent::Kind;

namespace {
// Feeds every word; returns the last event.
ReceiverEvent feed(CommandReceiver& receiver, const std::vector<Word>& words) {
  ReceiverEvent last{};
  for (Word w : words) last = receiver.on_word(w);
  return last;
}
}  // namespace

TEST(CommandReceiver, EveryCommandRoundTripsThroughTheStateMachine) {
  const std::vector<Command> commands = {DriveForDuration{50, 2}, TurnForDuration{-40, 1.5}, DriveForward{33},
                                         Turn{-75}, Stop{}};
  for (const Command& sent : commands) {
    CommandReceiver receiver;
    const ReceiverEvent event = feed(receiver, encode(sent));
    ASSERT_EQ(event.kind, Kind::CommandReady) << describe(sent);
    EXPECT_EQ(describe(*event.command), describe(quantised(sent)));
    EXPECT_EQ(receiver.state(), ReceiverState::Idle);
  }
}

TEST(CommandReceiver, ResetAloneEntersModeSelect) {
  CommandReceiver receiver;
  const ReceiverEvent event = receiver.on_word(kResetWord);
  EXPECT_EQ(event.kind, Kind::Reset);
  EXPECT_EQ(receiver.state(), ReceiverState::ModeSelect);
}

TEST(CommandReceiver, WordsBeforeAnyResetAreIgnored) {
  CommandReceiver receiver;
  for (Word w : {2, 0x620, 6}) {
    const ReceiverEvent event = receiver.on_word(static_cast<Word>(w));
    EXPECT_EQ(event.kind, Kind::Ignored);
    EXPECT_FALSE(event.reason.empty());
  }
  EXPECT_EQ(receiver.state(), ReceiverState::Idle);
}

TEST(CommandReceiver, ResetAtAnyPointAbandonsThePendingCommand) {
  CommandReceiver receiver;
  receiver.on_word(kResetWord);
  receiver.on_word(static_cast<Word>(Mode::DriveForDuration));
  ASSERT_EQ(receiver.state(), ReceiverState::AwaitingParameter);
  EXPECT_EQ(receiver.on_word(kResetWord).kind, Kind::Reset);
  EXPECT_FALSE(receiver.pending_mode());
  // The next word is a mode again, not a parameter.
  const ReceiverEvent event = receiver.on_word(static_cast<Word>(Mode::Turn));
  EXPECT_EQ(event.kind, Kind::ModeSelected);
  EXPECT_EQ(*event.mode, Mode::Turn);
}

TEST(CommandReceiver, StopCompletesWithoutAParameter) {
  CommandReceiver receiver;
  const ReceiverEvent event = feed(receiver, {kResetWord, static_cast<Word>(Mode::Stop)});
  ASSERT_EQ(event.kind, Kind::CommandReady);
  EXPECT_TRUE(std::holds_alternative<Stop>(*event.command));
}

TEST(CommandReceiver, UnknownModesAreIgnoredAndModeSelectKept) {
  CommandReceiver receiver;
  receiver.on_word(kResetWord);
  for (Word w : {7, 100, 4095}) {
    EXPECT_EQ(receiver.on_word(static_cast<Word>(w)).kind, Kind::Ignored);
    EXPECT_EQ(receiver.state(), ReceiverState::ModeSelect);
  }
  EXPECT_EQ(receiver.on_word(static_cast<Word>(Mode::ModeSelect)).kind, Kind::Ignored);
  EXPECT_EQ(receiver.on_word(static_cast<Word>(Mode::DriveForward)).kind, Kind::ModeSelected);
}

TEST(CommandReceiver, ACommandNeedsAFreshResetAfterItCompletes) {
  CommandReceiver receiver;
  feed(receiver, encode(DriveForward{20}));
  // A repeated parameter word (a duplicate frame) must not start anything.
  EXPECT_EQ(receiver.on_word(*parameter_word(DriveForward{20})).kind, Kind::Ignored);
}

TEST(CommandReceiver, ABadParameterDropsTheWholeCommand) {
  CommandReceiver receiver;
  receiver.on_word(kResetWord);
  receiver.on_word(static_cast<Word>(Mode::DriveForDuration));
  const ReceiverEvent event = receiver.on_word(0x040);  // speed field code 0
  EXPECT_EQ(event.kind, Kind::Ignored);
  EXPECT_EQ(receiver.state(), ReceiverState::Idle);
  EXPECT_FALSE(event.command);
}
