// Command abstraction layer: commands to words and back, field by field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "command/word_codec.h"

using namespace dtmf::command;

TEST(WordCodec, EveryCommandStartsWithResetThenItsMode) {
  EXPECT_EQ(encode(Reset{}), (std::vector<Word>{0}));
  EXPECT_EQ(encode(Stop{}), (std::vector<Word>{0, 6}));
  EXPECT_EQ(encode(DriveForDuration{50, 3})[1], 2);
  EXPECT_EQ(encode(TurnForDuration{-20, 1})[1], 3);
  EXPECT_EQ(encode(DriveForward{10})[1], 4);
  EXPECT_EQ(encode(Turn{10})[1], 5);
  EXPECT_EQ(encode(DriveForDuration{50, 3}).size(), 3u);
  EXPECT_EQ(encode(Turn{10}).size(), 3u);
}

TEST(WordCodec, DurationModesPackDurationHighAndVelocityLow) {
  // duration 8 s -> code 63 in bits 11..6; speed 100 -> code 63 in bits 5..0.
  EXPECT_EQ(*parameter_word(DriveForDuration{100, 8}), 0xFFF);
  // The lowest codes are 1: zero speed for zero seconds is word 0x041, never RESET.
  EXPECT_EQ(*parameter_word(DriveForDuration{0, 0}), 0x041);
  // Zero rotation is the middle code 32.
  EXPECT_EQ(*parameter_word(TurnForDuration{0, 0}) & 0x3F, 32);
  EXPECT_EQ(*parameter_word(TurnForDuration{-100, 0}), 0x041);
}

TEST(WordCodec, ContinuousModesUseAllTwelveBits) {
  EXPECT_EQ(*parameter_word(DriveForward{0}), 1);
  EXPECT_EQ(*parameter_word(DriveForward{100}), 4095);
  EXPECT_EQ(*parameter_word(Turn{-100}), 1);
  EXPECT_EQ(*parameter_word(Turn{0}), 2048);
  EXPECT_EQ(*parameter_word(Turn{100}), 4095);
}

TEST(WordCodec, NoParameterWordIsEverTheResetWord) {
  for (double v = 0; v <= 100; v += 0.5) {
    for (double d = 0; d <= 8; d += 0.25) {
      EXPECT_NE(*parameter_word(DriveForDuration{v, d}), kResetWord);
      EXPECT_NE(*parameter_word(TurnForDuration{v * 2 - 100, d}), kResetWord);
    }
    EXPECT_NE(*parameter_word(DriveForward{v}), kResetWord);
    EXPECT_NE(*parameter_word(Turn{v * 2 - 100}), kResetWord);
  }
}

TEST(WordCodec, RoundTripIsWithinHalfAStepForEveryField) {
  for (const FieldSpec* field : {&kDurationField, &kSpeedField6, &kRotationField6, &kSpeedField12, &kRotationField12}) {
    const double step = field_step(*field);
    for (int i = 0; i <= 1000; ++i) {
      const double value = field->min + (field->max - field->min) * i / 1000.0;
      const double back = *decode_field(*field, encode_field(*field, value));
      EXPECT_LE(std::abs(back - value), step / 2 + 1e-9) << field->name << " " << value;
    }
    EXPECT_DOUBLE_EQ(*decode_field(*field, encode_field(*field, field->min)), field->min);
    EXPECT_DOUBLE_EQ(*decode_field(*field, encode_field(*field, field->max)), field->max);
  }
  EXPECT_NEAR(field_step(kDurationField), 8.0 / 62, 1e-12);
  EXPECT_NEAR(field_step(kSpeedField12), 100.0 / 4094, 1e-12);
}

TEST(WordCodec, QuantisedCommandKeepsTheSeedResolutions) {
  const auto drive = std::get<DriveForDuration>(quantised(DriveForDuration{50, 2}));
  EXPECT_DOUBLE_EQ(drive.speed_percent, 50.0);  // 50 % is exactly code 32
  EXPECT_NEAR(drive.duration_s, 2.0, 8.0 / 62 / 2);
  const auto turn = std::get<Turn>(quantised(Turn{0}));
  EXPECT_DOUBLE_EQ(turn.rotation_percent, 0.0);
}

TEST(WordCodec, OutOfRangeValuesAreRefusedNamingFieldAndRange) {
  try {
    encode(DriveForDuration{120, 1});
    FAIL() << "speed 120 accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.field(), "speed_percent");
    EXPECT_NE(std::string(e.what()).find("0..100"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("120"), std::string::npos) << e.what();
  }
  EXPECT_THROW(encode(DriveForDuration{50, -0.1}), ParameterError);
  EXPECT_THROW(encode(DriveForDuration{50, 8.01}), ParameterError);
  EXPECT_THROW(encode(TurnForDuration{-100.5, 1}), ParameterError);
  EXPECT_THROW(encode(Turn{101}), ParameterError);
  EXPECT_THROW(encode(DriveForward{-1}), ParameterError);
  EXPECT_THROW(encode(DriveForward{std::numeric_limits<double>::quiet_NaN()}), ParameterError);
  EXPECT_THROW(encode(Turn{std::numeric_limits<double>::infinity()}), ParameterError);
  try {
    encode(TurnForDuration{0, 9});
    FAIL() << "duration 9 accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.field(), "duration_s");
    EXPECT_NE(std::string(e.what()).find("0..8"), std::string::npos) << e.what();
  }
}

TEST(WordCodec, ParameterWordsWithAnUnusedZeroCodeAreRejected) {
  EXPECT_FALSE(decode_parameters(Mode::DriveForDuration, 0x040).command);  // speed code 0
  EXPECT_FALSE(decode_parameters(Mode::TurnForDuration, 0x001).command);   // duration code 0
  EXPECT_NE(decode_parameters(Mode::DriveForDuration, 0x040).error.find("speed_percent"), std::string::npos);
  EXPECT_FALSE(decode_parameters(Mode::Stop, 0x123).command);
}

TEST(WordCodec, DescribeNamesModeAndParameters) {
  EXPECT_EQ(describe(DriveForDuration{50, 3}), "drive_for_duration speed=50.0% duration=3.00s");
  EXPECT_EQ(describe(Stop{}), "stop");
  EXPECT_EQ(kind_name(Turn{5}), "turn");
  EXPECT_EQ(mode_name(Mode::DriveForward), "drive_forward");
  EXPECT_FALSE(mode_from_word(0));
  EXPECT_FALSE(mode_from_word(7));
  EXPECT_EQ(*mode_from_word(6), Mode::Stop);
}
