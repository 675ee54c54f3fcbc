// dtmfctl's progress lines for a frame the air holds (issue 59): "waiting for the air: <why>",
// in plain lines and in --json; and an event a newer server sends that this client does not
// know is shown by its number, not a crash.
#include "progress_view.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

using namespace dtmf;

namespace {

v1::Progress waiting() {
  v1::Progress p;
  p.set_event(v1::FRAME_EVENT_WAITING_FOR_AIR);
  p.set_command("drive_for_duration speed=30.0% duration=0.50s");
  p.set_frame_index(0);
  p.set_frame_count(1);
  p.set_attempt(1);
  p.set_air_wait_reason("sound 14 dB over the room's floor");
  p.set_air_wait_left_ms(8700);
  p.set_detail("waiting for the air: sound 14 dB over the room's floor");
  return p;
}

std::string shown(const v1::Progress& p, bool json) {
  ::testing::internal::CaptureStdout();
  cli::ProgressView(json, false).show(p);
  return ::testing::internal::GetCapturedStdout();
}

}  // namespace

TEST(ProgressView, AFrameTheAirHoldsSaysWhyAndForHowLongAtMost) {
  EXPECT_EQ(shown(waiting(), false),
            "drive_for_duration speed=30.0% duration=0.50s: frame 1/1 waiting for the air: sound 14 dB over the "
            "room's floor (at most 8.7 s)\n");
  const auto json = nlohmann::json::parse(shown(waiting(), true));
  EXPECT_EQ(json["event"], "waiting_for_air");
  EXPECT_EQ(json["air_wait_reason"], "sound 14 dB over the room's floor");
  EXPECT_EQ(json["air_wait_left_ms"], 8700);
  EXPECT_EQ(json["detail"], "waiting for the air: sound 14 dB over the room's floor");
}

TEST(ProgressView, ATransmissionThatWaitedSaysHowLong) {
  v1::Progress p;
  p.set_event(v1::FRAME_EVENT_TRANSMITTING);
  p.set_frame_count(1);
  p.set_attempt(1);
  p.set_sequence(3);
  p.set_air_wait_ms(8712);
  EXPECT_NE(shown(p, false).find("(attempt 1) after 8.7 s waiting for the air"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(shown(p, true))["air_wait_ms"], 8712);
}

TEST(ProgressView, AnEventThisClientDoesNotKnowIsShownByItsNumber) {
  EXPECT_EQ(cli::event_name(static_cast<v1::FrameEvent>(99)), "event_99");
  EXPECT_EQ(cli::event_name(v1::FRAME_EVENT_WAITING_FOR_AIR), "waiting_for_air");
}
