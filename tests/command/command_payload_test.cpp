// The fast profile's command payload: every command in one 28-bit field, all or nothing.
#include <gtest/gtest.h>

#include "command/command_payload.h"
#include "command/robot_model.h"
#include "command/word_codec.h"

#include <cmath>

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
  // 5 TURN, 6 VELOCITY; 7 reserved.
  EXPECT_FALSE(decode_payload(0x6000000).command) << "a velocity of code 0";
  EXPECT_FALSE(decode_payload(0x6800000).command) << "a velocity without angular and lease codes";
  EXPECT_FALSE(decode_payload(0x6800800).command) << "a velocity with a lease of code 0";
  EXPECT_FALSE(decode_payload(0x7000000).command) << "kind 7 is reserved (extended frame)";
  EXPECT_FALSE(decode_payload(0x8000000).command) << "wider than 27 bits";
  EXPECT_FALSE(decode_payload(0x1002000).command) << "STOP with a field A other than every robot's";
  EXPECT_FALSE(decode_payload(0x1000001).command) << "STOP with a field B";
  EXPECT_FALSE(decode_payload(0x0000001).command) << "RESET with a field";
  EXPECT_FALSE(decode_payload(0x4800001).command) << "DRIVE_FORWARD with a duration";
  EXPECT_FALSE(decode_payload(0x2000800).command) << "a speed of code 0";
  const auto refused = decode_payload(0x2800000);
  EXPECT_FALSE(refused.command);
  EXPECT_NE(refused.error.find("0x2800000"), std::string::npos) << refused.error;
}

TEST(CommandPayload, AStopForEveryRobotIsStopWithFieldAOne) {
  EXPECT_EQ(encode_payload(Stop{true}), 0x1001000u);
  EXPECT_EQ(encode_payload(Stop{}), 0x1000000u) << "a robot's own stop is unchanged";
  const auto decoded = decode_payload(0x1001000);
  ASSERT_TRUE(decoded.command) << decoded.error;
  EXPECT_TRUE(every_robot(*decoded.command));
  EXPECT_FALSE(every_robot(*decode_payload(0x1000000).command));
  EXPECT_EQ(describe(*decoded.command), "stop every_robot");
  EXPECT_EQ(kind_name(*decoded.command), "stop");
  EXPECT_THROW(encode(Stop{true}), ParameterError) << "the seed's words name no robot";
}

TEST(CommandPayload, VelocityCarriesBothSpeedsAndTheLeaseFinerThanTurtlebot3Teleop) {
  const RobotModel& model = burger();
  // turtlebot3_teleop steps 0.01 m/s and 0.1 rad/s: the payload's steps must be finer.
  EXPECT_LT(field_step(kLinearFraction12) * model.max_linear_mps, 0.01 / 2);
  EXPECT_LT(field_step(kAngularFraction8) * model.max_angular_radps, 0.1 / 2);
  const std::uint32_t payload = encode_payload(velocity_command(model, -0.07, 0.3, 0.5));
  EXPECT_EQ(payload >> 24, 6u) << "kind VELOCITY";
  const auto decoded = decode_payload(payload);
  ASSERT_TRUE(decoded.command) << decoded.error;
  const auto v = std::get<Velocity>(*decoded.command);
  EXPECT_NEAR(linear_mps(model, v), -0.07, 0.0001) << "reverse survives";
  EXPECT_NEAR(angular_radps(model, v), 0.3, 0.012);
  EXPECT_DOUBLE_EQ(v.lease_s, 0.5) << "0.5, 1 and 2 s are exact";
  // Between two codes a lease is carried rounded down: never longer than asked.
  const auto lease_of = [](double s) { return std::get<Velocity>(quantised_payload(Velocity{0, 0, s})).lease_s; };
  EXPECT_DOUBLE_EQ(lease_of(1.0), 1.0);
  EXPECT_DOUBLE_EQ(lease_of(0.74), 0.625);
  EXPECT_DOUBLE_EQ(lease_of(1.999), 1.875);
  EXPECT_DOUBLE_EQ(lease_of(0.3), 0.25);
  EXPECT_DOUBLE_EQ(field_step(kLeaseField4), 0.125);
  // Zero is exact on both axes, and so are the ends of every range.
  const auto still = std::get<Velocity>(quantised_payload(Velocity{0, 0, 2.0}));
  EXPECT_EQ(still.linear_fraction, 0.0);
  EXPECT_EQ(still.angular_fraction, 0.0);
  EXPECT_DOUBLE_EQ(still.lease_s, 2.0);
  const auto full = std::get<Velocity>(quantised_payload(Velocity{-1, 1, 0.25}));
  EXPECT_DOUBLE_EQ(full.linear_fraction, -1.0);
  EXPECT_DOUBLE_EQ(full.angular_fraction, 1.0);
  EXPECT_DOUBLE_EQ(full.lease_s, 0.25);
  EXPECT_EQ(describe(full), "velocity linear=-100.0% angular=+100.0% lease=0.25s");
}

TEST(CommandPayload, VelocityBeyondTheRobotOrTheLeaseRangeIsRefusedNamingTheField) {
  const auto field_of = [](auto make) {
    try {
      make();
    } catch (const ParameterError& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of([] { velocity_command(burger(), 0.23, 0, 1); }), "linear_mps");
  EXPECT_EQ(field_of([] { velocity_command(burger(), 0, -2.9, 1); }), "angular_radps");
  EXPECT_EQ(field_of([] { velocity_command(burger(), 0, 0, 2.5); }), "lease_s");
  EXPECT_EQ(field_of([] { velocity_command(burger(), 0, 0, 0.2); }), "lease_s");
  EXPECT_EQ(field_of([] { velocity_command(waffle(), std::nan(""), 0, 1); }), "linear_mps");
  EXPECT_EQ(field_of([] { velocity_command(waffle(), 0.26, 1.82, 1); }), "accepted") << "the limits themselves";
  // The seed's 12-bit words cannot carry a velocity: the error names the profile.
  EXPECT_EQ(field_of([] { encode(Velocity{0.5, 0, 1}); }), "profile");
}
