// dtmfctl watch's lines, from the messages alone.
#include "watch_view.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace dtmf;

TEST(WatchView, AFramePlayedNamesItsRobotCommandAndCounter) {
  v1::WatchAirResponse m;
  m.set_audio_ms(1234.5);
  auto& f = *m.mutable_frame_played();
  f.set_command("drive speed=50.0%");
  f.add_robots("alpha");
  f.set_kind("command");
  f.set_profile("fast");
  f.set_frame_index(0);
  f.set_frame_count(1);
  f.set_attempt(2);
  f.set_sequence(5);
  f.set_counter(7001);
  f.set_authenticated(true);
  EXPECT_EQ(cli::watch_lines(m),
            "    1234.5 ms  frame     alpha        drive speed=50.0% fast, frame 1/1, attempt 2, sequence 5, counter "
            "7001, authenticated\n");
}

TEST(WatchView, WhatASlowWatcherLostComesFirst) {
  v1::WatchAirResponse m;
  m.set_audio_ms(10);
  m.set_dropped_events(3);
  m.set_dropped_columns(40);
  m.mutable_air_busy()->set_busy(false);
  EXPECT_EQ(cli::watch_lines(m),
            "(this watcher read too slowly: lost 3 events and 40 spectrum columns)\n"
            "      10.0 ms  air       quiet again\n");
}

TEST(WatchView, AnAnswerAndItsFrame) {
  v1::WatchAirResponse heard;
  heard.mutable_answer_heard()->set_ack(true);
  heard.mutable_answer_heard()->set_profile("fast");
  heard.mutable_answer_heard()->set_robot("beta");
  heard.mutable_answer_heard()->set_sequence(9);
  heard.mutable_answer_heard()->set_level_dbfs(-31.25);
  EXPECT_EQ(cli::watch_lines(heard), "       0.0 ms  heard     beta         ACK fast, sequence 9, -31.2 dBFS\n");
  v1::WatchAirResponse answered;
  auto& a = *answered.mutable_frame_answered();
  a.set_robot("beta");
  a.set_answer("ack");
  a.set_attempt(1);
  a.set_authenticated(true);
  a.set_response_time_ms(182);
  EXPECT_EQ(cli::watch_lines(answered),
            "       0.0 ms  answered  beta         frame 1 attempt 1: ack (authenticated) after 182 ms\n");
}

TEST(WatchView, ASpectrumColumnSaysWhereItsLoudestBinIs) {
  v1::WatchAirResponse m;
  auto& c = *m.mutable_spectrum();
  c.set_low_hz(1000);
  c.set_step_hz(100);
  for (int i = 0; i < 10; ++i) c.add_level_dbfs(i == 3 ? -20.0f : -90.0f);
  EXPECT_EQ(cli::watch_lines(m), "       0.0 ms  spectrum  1000-2000 Hz in 10 bins: loudest -20.0 dBFS at 1350 Hz\n");
}

TEST(WatchView, JsonIsOneObjectPerMessageWithTheProtosNames) {
  v1::WatchAirResponse m;
  m.set_audio_ms(5);
  m.mutable_command_ended()->set_outcome("confirmed");
  const std::string line = cli::watch_json(m);
  ASSERT_EQ(line.back(), '\n');
  const auto json = nlohmann::json::parse(line);
  EXPECT_EQ(json["command_ended"]["outcome"], "confirmed");
  EXPECT_EQ(json["audio_ms"], 5);
  EXPECT_EQ(json["dropped_events"], "0");  // uint64 is a string in proto3 JSON
}

TEST(WatchView, AReceptionSaysWhatTheRobotDidAndWhy) {
  v1::Reception r;
  r.set_robot("alpha");
  r.set_profile("fast");
  r.set_event("refused");
  r.set_reason("authentication");
  r.set_heard_unix_ms(1765091464512);
  const std::string line = cli::reception_line(r);
  EXPECT_NE(line.find(".512  alpha        fast  refused   authentication, not answered\n"), std::string::npos) << line;
  r.set_event("command");
  r.set_reason("");
  r.set_command("stop");
  r.set_linear_mps(0);
  r.set_angular_radps(0);
  r.set_authenticated(true);
  r.set_reply("ack");
  EXPECT_NE(cli::reception_line(r).find("command   stop, 0.00 m/s 0.00 rad/s, authenticated, answered ack\n"),
            std::string::npos)
      << cli::reception_line(r);
}
