// The fast profile's command payload: every command in one 28-bit field, all or nothing.
#include <gtest/gtest.h>

#include "command/command_payload.h"

using namespace dtmf::command;

TEST(CommandPayload, EveryKindComesBackAtTwelveBitResolution) {
  const double speed_step = field_step(kSpeedField12), duration_step = field_step(kDurationField12);
  EXPECT_LT(duration_step, 0.002);

  auto round_trip = [](const Command& c) {
    const auto decoded = decode_payload(encode_payload(c));
    EXPECT_TRUE(decoded.command) << describe(c) << ": " << decoded.error;
    return decoded.command.value_or(Reset{});
  };
  const auto d = std::get<DriveForDuration>(round_trip(DriveForDuration{37.5, 2.25}));
  EXPECT_NEAR(d.speed_percent, 37.5, speed_step / 2);
  EXPECT_NEAR(d.duration_s, 2.25, duration_step / 2);
  const auto t = std::get<TurnForDuration>(round_trip(TurnForDuration{-80, 7.9}));
  EXPECT_NEAR(t.rotation_percent, -80, field_step(kRotationField12) / 2);
  EXPECT_NEAR(t.duration_s, 7.9, duration_step / 2);
  EXPECT_DOUBLE_EQ(std::get<DriveForward>(round_trip(DriveForward{100})).speed_percent, 100);
  EXPECT_DOUBLE_EQ(std::get<Turn>(round_trip(Turn{0})).rotation_percent, 0);
  EXPECT_TRUE(std::holds_alternative<Stop>(round_trip(Stop{})));
  EXPECT_TRUE(std::holds_alternative<Reset>(round_trip(Reset{})));
}

TEST(CommandPayload, OutOfRangeValuesAreRefusedNamingTheField) {
  try {
    encode_payload(DriveForDuration{50, 9});
    FAIL() << "9 s accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.field(), "duration_s");
  }
  EXPECT_THROW(encode_payload(Turn{-101}), ParameterError);
}

TEST(CommandPayload, PayloadsThatNoSenderMakesAreRefused) {
  // Kinds: 0 RESET, 1 STOP, 2 DRIVE_FOR_DURATION, 3 TURN_FOR_DURATION, 4 DRIVE_FORWARD,
  // 5 TURN; 6 and 7 reserved.
  EXPECT_FALSE(decode_payload(0x6000000).command) << "kind 6 is reserved (velocity)";
  EXPECT_FALSE(decode_payload(0x7000000).command) << "kind 7 is reserved (extended frame)";
  EXPECT_FALSE(decode_payload(0x8000000).command) << "wider than 27 bits";
  EXPECT_FALSE(decode_payload(0x1001000).command) << "STOP with a field";
  EXPECT_FALSE(decode_payload(0x0000001).command) << "RESET with a field";
  EXPECT_FALSE(decode_payload(0x4800001).command) << "DRIVE_FORWARD with a duration";
  EXPECT_FALSE(decode_payload(0x2000800).command) << "a speed of code 0";
  const auto refused = decode_payload(0x2800000);
  EXPECT_FALSE(refused.command);
  EXPECT_NE(refused.error.find("0x2800000"), std::string::npos) << refused.error;
}
