// Database: run_report() on rows built to match the seed's Appendix A tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "command/test_sequence.h"
#include "link/seed_sender_path.h"
#include "profile/link_profile.h"
#include "run_reader.h"
#include "store.h"
#include "temp_database.h"

using namespace dtmf;
using namespace dtmf::store;
using dtmf::test_support::TempDatabase;
using std::chrono::milliseconds;

namespace {

struct Transmission {
  std::string command_id;
  int position;
  link::SeedPlannedFrame frame;
};

// The seed's 65 frames, one 3 s slot each (room for a retransmission at +1.5 s).
constexpr int kSlotMs = 3000;

std::vector<Transmission> sequence_transmissions(Store& store, const std::string& run_id, WallTime t0) {
  std::vector<Transmission> all;
  int slot = 0;
  for (const auto& command : command::seed_test_sequence()) {
    const auto frames = link::plan_command(seed_profile(), command);
    CommandRow row;
    row.run_id = run_id;
    row.kind = command::kind_name(command);
    row.profile = "seed";
    row.frame_count = static_cast<int>(frames.size());
    row.requested_at = t0 + milliseconds(slot * kSlotMs);
    row.outcome = "confirmed";
    store.write(row);
    for (std::size_t p = 0; p < frames.size(); ++p, ++slot) all.push_back({row.id, static_cast<int>(p), frames[p]});
  }
  return all;
}

FrameAttemptRow attempt_row(const std::string& run_id, const Transmission& t, int attempt, WallTime start) {
  FrameAttemptRow a;
  a.run_id = run_id;
  a.command_id = t.command_id;
  a.position = t.position;
  a.attempt = attempt;
  a.word = t.frame.word;
  a.frame = std::to_string(t.frame.frame);
  a.tones_hz.assign(t.frame.tones_hz.begin(), t.frame.tones_hz.end());
  a.chord_started_at = start;
  a.chord_ended_at = start + milliseconds(800);
  a.answer = "none";
  return a;
}

ReceptionRow reception_row(int frame, bool crc_ok, WallTime heard) {
  ReceptionRow r;
  r.host = "robot";
  r.profile = "seed";
  r.heard_at = heard;
  r.frame = std::to_string(frame);
  r.crc_ok = crc_ok;
  r.reply = crc_ok ? "ack" : "nack";
  return r;
}

double as_double(const pqxx::field& f) { return f.as<double>(); }

}  // namespace

TEST(RunReport, ReproducesTheSeedsNoisePollutedTable) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/report-" + std::to_string(::getpid()) + ".spill";
  const WallTime t0 = WallClock::now() - std::chrono::hours(1);
  TestRunRow run;
  run.label = "noise";
  run.profile = "seed";
  run.started_at = t0 - milliseconds(100);
  run.ended_at = t0 + milliseconds(65 * kSlotMs);

  std::vector<double> latencies, responses;
  {
    Store store(options);
    store.write(run);
    const auto transmissions = sequence_transmissions(store, run.id, t0);
    ASSERT_EQ(transmissions.size(), 65u);
    constexpr int kDropped = 40;    // heard by no one
    constexpr int kConfirmed = 28;  // the first 28 heard ACKs; the rest went unconfirmed
    for (int i = 0; i < 65; ++i) {
      const Transmission& t = transmissions[static_cast<std::size_t>(i)];
      const WallTime start = t0 + milliseconds(i * kSlotMs);
      FrameAttemptRow first = attempt_row(run.id, t, 1, start);
      if (i < kConfirmed) {
        const double response = 880 + (i * 13) % 200;
        first.answer = "ack";
        first.answered_at = start + milliseconds(static_cast<int>(response));
        responses.push_back(response);
      }
      store.write(first);
      if (i >= kConfirmed) store.write(attempt_row(run.id, t, 2, start + milliseconds(1500)));
      if (i != kDropped) {
        const double latency = 150 + (i * 37) % 500;
        store.write(reception_row(t.frame.frame, true, start + milliseconds(static_cast<int>(latency))));
        latencies.push_back(latency);
      }
    }
    // One intact frame nobody sent (a false positive), four corrupted ones (NACKed).
    store.write(reception_row(reliability::word_frame_make(0x123), true, t0 + milliseconds(10 * kSlotMs + 2500)));
    for (int k = 0; k < 4; ++k) {
      store.write(reception_row(reliability::word_frame_make(0x456) ^ (1 << k), false,
                                t0 + milliseconds((20 + k) * kSlotMs + 2600)));
    }
    // A reception outside the run's time does not count at all.
    store.write(reception_row(reliability::word_frame_make(0x789), true, t0 - std::chrono::minutes(5)));
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }

  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const pqxx::row r = tx.exec("SELECT * FROM run_report('" + run.id + "'::uuid)")[0];
  EXPECT_EQ(r["label"].as<std::string>(), "noise");
  EXPECT_EQ(r["transmissions_sent"].as<int>(), 65);
  EXPECT_EQ(r["frame_attempts"].as<int>(), 65 + 37);
  EXPECT_EQ(r["transmissions_received"].as<int>(), 69);
  EXPECT_EQ(r["successfully_matched"].as<int>(), 64);
  EXPECT_EQ(r["successful_transmissions"].as<int>(), 64);
  EXPECT_EQ(r["dropped"].as<int>(), 1);
  EXPECT_EQ(r["false_positives"].as<int>(), 1);
  EXPECT_EQ(r["duplicates"].as<int>(), 0);
  EXPECT_DOUBLE_EQ(as_double(r["false_positive_rate_pct"]), 1.54);
  EXPECT_DOUBLE_EQ(as_double(r["success_rate_pct"]), 98.46);
  EXPECT_EQ(r["sender_confirmed"].as<int>(), 28);
  EXPECT_DOUBLE_EQ(as_double(r["sender_confirmed_rate_pct"]), 43.08);
  EXPECT_EQ(r["crc_accepted"].as<int>(), 65);
  EXPECT_EQ(r["crc_rejected"].as<int>(), 4);
  EXPECT_EQ(r["negative_confirmations_sent"].as<int>(), 4);
  EXPECT_DOUBLE_EQ(as_double(r["error_catch_rate_pct"]), 80.0);

  const auto avg = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); };
  EXPECT_NEAR(as_double(r["response_time_avg_ms"]), avg(responses), 0.01);
  EXPECT_NEAR(as_double(r["response_time_min_ms"]), *std::min_element(responses.begin(), responses.end()), 0.01);
  EXPECT_NEAR(as_double(r["response_time_max_ms"]), *std::max_element(responses.begin(), responses.end()), 0.01);
  EXPECT_NEAR(as_double(r["latency_avg_ms"]), avg(latencies), 0.01);
  EXPECT_NEAR(as_double(r["latency_min_ms"]), *std::min_element(latencies.begin(), latencies.end()), 0.01);
  EXPECT_NEAR(as_double(r["latency_max_ms"]), *std::max_element(latencies.begin(), latencies.end()), 0.01);

  // The same report by run number, and the run in the runs view.
  const auto number = tx.exec("SELECT number FROM test_runs WHERE id = '" + run.id + "'")[0][0].as<long>();
  EXPECT_EQ(
      tx.exec("SELECT success_rate_pct FROM run_report(" + std::to_string(number) + "::bigint)")[0][0].as<double>(),
      98.46);
  EXPECT_EQ(tx.exec("SELECT transmissions_sent FROM runs WHERE number = " + std::to_string(number))[0][0].as<int>(),
            65);

  // run_frames: every chord once, in order, with the same matches as the report.
  const pqxx::result frames = tx.exec("SELECT * FROM run_frames(" + std::to_string(number) + "::bigint)");
  ASSERT_EQ(frames.size(), 65u + 37u);
  std::vector<double> frame_latencies, frame_responses;
  for (const auto& f : frames) {
    if (!f["latency_ms"].is_null()) frame_latencies.push_back(as_double(f["latency_ms"]));
    if (!f["response_time_ms"].is_null()) frame_responses.push_back(as_double(f["response_time_ms"]));
  }
  EXPECT_EQ(frame_latencies, latencies);  // in the order played; the retransmissions were not heard
  EXPECT_EQ(frame_responses, responses);
  EXPECT_EQ(frames[0]["command_kind"].as<std::string>(), "reset");
  EXPECT_EQ(frames[0]["frame_bits"].as<std::string>().size(), 16u);
  EXPECT_EQ(frames[0]["attempt"].as<int>(), 1);
}

TEST(RunReport, ACleanRunIsAllSuccessWithNoErrorCatchRate) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/report-clean-" + std::to_string(::getpid()) + ".spill";
  const WallTime t0 = WallClock::now() - std::chrono::hours(2);
  TestRunRow run;
  run.label = "general";
  run.profile = "seed";
  run.started_at = t0;
  run.ended_at = t0 + milliseconds(65 * kSlotMs);
  {
    Store store(options);
    store.write(run);
    const auto transmissions = sequence_transmissions(store, run.id, t0);
    for (int i = 0; i < 65; ++i) {
      const WallTime start = t0 + milliseconds(i * kSlotMs);
      FrameAttemptRow a = attempt_row(run.id, transmissions[static_cast<std::size_t>(i)], 1, start);
      a.answer = "ack";
      a.answered_at = start + milliseconds(887);
      store.write(a);
      store.write(reception_row(std::stoi(a.frame), true, start + milliseconds(199)));
    }
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const pqxx::row r = tx.exec("SELECT * FROM run_report('" + run.id + "'::uuid)")[0];
  EXPECT_EQ(r["successfully_matched"].as<int>(), 65);
  EXPECT_DOUBLE_EQ(as_double(r["success_rate_pct"]), 100.0);
  EXPECT_DOUBLE_EQ(as_double(r["sender_confirmed_rate_pct"]), 100.0);
  EXPECT_DOUBLE_EQ(as_double(r["false_positive_rate_pct"]), 0.0);
  EXPECT_TRUE(r["error_catch_rate_pct"].is_null());  // the seed's "N/A"
  EXPECT_DOUBLE_EQ(as_double(r["latency_avg_ms"]), 199.0);
  EXPECT_DOUBLE_EQ(as_double(r["response_time_max_ms"]), 887.0);
}

TEST(RunReport, ARetransmissionHeardAgainIsADuplicateAndAChordHeardTwiceAFalsePositive) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/report-dup-" + std::to_string(::getpid()) + ".spill";
  const WallTime t0 = WallClock::now() - std::chrono::hours(3);
  TestRunRow run;
  run.label = "duplicates";
  run.profile = "seed";
  run.started_at = t0;
  run.ended_at = t0 + milliseconds(2 * kSlotMs);
  {
    Store store(options);
    store.write(run);
    CommandRow command;
    command.run_id = run.id;
    command.kind = "reset";
    command.profile = "seed";
    command.requested_at = t0;
    command.outcome = "confirmed";
    store.write(command);
    const Transmission t{command.id, 0, link::plan_word(seed_profile(), 0)};
    store.write(attempt_row(run.id, t, 1, t0));                       // ACK lost ...
    store.write(attempt_row(run.id, t, 2, t0 + milliseconds(1500)));  // ... so sent again
    store.write(reception_row(t.frame.frame, true, t0 + milliseconds(150)));
    store.write(reception_row(t.frame.frame, true, t0 + milliseconds(1650)));  // the retransmission
    store.write(reception_row(t.frame.frame, true, t0 + milliseconds(2350)));  // its tail, passed twice
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const pqxx::row r = tx.exec("SELECT * FROM run_report('" + run.id + "'::uuid)")[0];
  EXPECT_EQ(r["transmissions_sent"].as<int>(), 1);
  EXPECT_EQ(r["successfully_matched"].as<int>(), 1);
  EXPECT_EQ(r["duplicates"].as<int>(), 1);
  EXPECT_EQ(r["false_positives"].as<int>(), 1);
  EXPECT_DOUBLE_EQ(as_double(r["latency_max_ms"]), 150.0);

  // Per frame: the first attempt got the first reception, the retransmission its own.
  const pqxx::result frames = tx.exec("SELECT attempt, latency_ms FROM run_frames('" + run.id + "'::uuid)");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0][0].as<int>(), 1);
  EXPECT_DOUBLE_EQ(as_double(frames[0][1]), 150.0);
  EXPECT_EQ(frames[1][0].as<int>(), 2);
  EXPECT_DOUBLE_EQ(as_double(frames[1][1]), 150.0);
}

// Frames the robot refused (docs/security.md) match no attempt and are no false positive: the
// report counts them on their own, those that failed authentication apart, and RunReader
// (GetReport, dtmfctl report) reads the counts.
TEST(RunReport, RefusedFramesAreCountedAndAreNoFalsePositives) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/report-refused-" + std::to_string(::getpid()) + ".spill";
  const WallTime t0 = WallClock::now() - std::chrono::hours(4);
  TestRunRow run;
  run.label = "forgery";
  run.profile = "fast";
  run.started_at = t0;
  run.ended_at = t0 + milliseconds(4000);
  {
    Store store(options);
    store.write(run);
    const auto refused = [&](int frame, const std::string& reason, int at_ms) {
      ReceptionRow r = reception_row(frame, true, t0 + milliseconds(at_ms));
      r.profile = "fast";
      r.frame_width = 80;
      r.event = "refused";
      r.reason = reason;
      r.reply = "nack";
      store.write(r);
    };
    refused(0x1234, "authentication", 500);   // a forged MAC
    refused(0x5678, "authentication", 1500);  // a replay: a counter not newer
    refused(0x9abc, "payload", 2500);         // a kind this robot does not know
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  {
    pqxx::connection c(db.url());
    pqxx::work tx(c);
    const pqxx::row r = tx.exec("SELECT * FROM run_report('" + run.id + "'::uuid)")[0];
    EXPECT_EQ(r["refused"].as<int>(), 3);
    EXPECT_EQ(r["refused_authentication"].as<int>(), 2);
    EXPECT_EQ(r["false_positives"].as<int>(), 0);
    EXPECT_EQ(r["crc_accepted"].as<int>(), 0);
  }
  const auto report = RunReader(db.url()).report(run.id, false);
  ASSERT_TRUE(report);
  EXPECT_EQ(report->refused, 3);
  EXPECT_EQ(report->refused_authentication, 2);
}

// Migration 009: a burst of authentication refusals shows as the most in any 60 s, and a
// transmission confirmed by an untagged ACK (a frame without a MAC) is counted apart from
// the keyed confirmations.
TEST(RunReport, ABurstOfForgeriesShowsAsItsPeakAndUntaggedConfirmationsApart) {
  TempDatabase db;
  StoreOptions options;
  options.database = db.url();
  options.spill_path = ::testing::TempDir() + "/report-burst-" + std::to_string(::getpid()) + ".spill";
  const WallTime t0 = WallClock::now() - std::chrono::hours(5);
  TestRunRow run;
  run.label = "burst";
  run.profile = "fast";
  run.started_at = t0;
  run.ended_at = t0 + std::chrono::minutes(5);
  {
    Store store(options);
    store.write(run);
    const auto refused = [&](int frame, WallTime at) {
      ReceptionRow r = reception_row(frame, true, at);
      r.profile = "fast";
      r.frame_width = 80;
      r.event = "refused";
      r.reason = "authentication";
      r.reply = "nack";
      store.write(r);
    };
    // Three spread over the first two minutes, then twelve within 30 s.
    for (int i = 0; i < 3; ++i) refused(0x100 + i, t0 + std::chrono::seconds(40 * i));
    for (int i = 0; i < 12; ++i) refused(0x200 + i, t0 + std::chrono::seconds(180) + milliseconds(2500 * i));
    // Two confirmed transmissions: one with a tagged ACK, one with an untagged one.
    const auto transmissions = sequence_transmissions(store, run.id, t0);
    for (int i = 0; i < 2; ++i) {
      FrameAttemptRow a =
          attempt_row(run.id, transmissions[static_cast<std::size_t>(i)], 1, t0 + milliseconds(i * kSlotMs));
      a.answer = "ack";
      a.answered_at = a.chord_started_at + milliseconds(300);
      a.authenticated = i == 0;
      store.write(a);
    }
    ASSERT_TRUE(store.flush(std::chrono::seconds(30)));
  }
  pqxx::connection c(db.url());
  pqxx::work tx(c);
  const pqxx::row r = tx.exec("SELECT * FROM run_report('" + run.id + "'::uuid)")[0];
  EXPECT_EQ(r["refused_authentication"].as<int>(), 15);
  EXPECT_EQ(r["refused_authentication_peak_per_minute"].as<int>(), 12);
  EXPECT_EQ(r["sender_confirmed"].as<int>(), 2);
  EXPECT_EQ(r["sender_confirmed_unauthenticated"].as<int>(), 1);
  const auto report = RunReader(db.url()).report(run.id, false);
  ASSERT_TRUE(report);
  EXPECT_EQ(report->refused_authentication_peak_per_minute, 12);
  EXPECT_EQ(report->sender_confirmed_unauthenticated, 1);
}
