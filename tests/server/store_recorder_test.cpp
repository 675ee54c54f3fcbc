// The sender's log kept from progress events alone: which rows each event writes, and that an
// update keeps the row it updates (the store upserts by id).
#include "store_recorder.h"

#include <gtest/gtest.h>

#include "link/link.h"

using namespace dtmf;
using namespace dtmf::server;
using Kind = ProgressEvent::Kind;

namespace {

const store::CommandRow& command_in(const TransmissionRecord::Row& row) {
  EXPECT_TRUE(std::holds_alternative<store::CommandRow>(row));
  return std::get<store::CommandRow>(row);
}
const store::FrameAttemptRow& attempt_in(const TransmissionRecord::Row& row) {
  EXPECT_TRUE(std::holds_alternative<store::FrameAttemptRow>(row));
  return std::get<store::FrameAttemptRow>(row);
}

// The links the jobs are planned with, one per profile, for the whole test program.
link::Link& link_of(const LinkProfile& profile) {
  static const auto links = link::make_links({});
  for (const auto& l : links) {
    if (&l->profile() == &profile) return *l;
  }
  throw std::invalid_argument(profile.name);
}

std::unique_ptr<Job> drive_job(const LinkProfile& profile) {
  auto job = std::make_unique<Job>(link_of(profile), command::DriveForDuration{50, 2}, Policy::Fail,
                                   std::chrono::seconds(1), std::optional<std::string>("run-1"));
  job->plan();
  return job;
}

// An event about frame `frame_index` of `job`, as the transmitter makes it.
ProgressEvent event(Kind kind, int frame_index = 0, int attempt = 0, const Job* job = nullptr) {
  ProgressEvent e{kind};
  e.frame_index = frame_index;
  e.attempt = attempt;
  if (job) {
    e.frame = job->frames().at(static_cast<std::size_t>(frame_index));
    e.frame_count = job->frame_count();
  }
  return e;
}

}  // namespace

TEST(StoreRecorder, ACommandWithARetransmissionIsOneCommandRowAndOneRowPerAttempt) {
  const auto job = drive_job(seed_profile());
  ASSERT_GE(job->frames().size(), 1u);
  TransmissionRecord record("sender-pc");

  ProgressEvent queued = event(Kind::Queued);
  auto rows = record.on_event(*job, queued);
  ASSERT_EQ(rows.size(), 1u);
  const store::CommandRow first = command_in(rows[0]);
  EXPECT_EQ(first.id, job->id());
  EXPECT_EQ(first.run_id, "run-1");
  EXPECT_EQ(first.kind, "drive_for_duration");
  EXPECT_EQ(first.parameters["speed_percent"], 50);
  EXPECT_EQ(first.parameters["duration_s"], 2);
  EXPECT_EQ(first.profile, "seed");
  EXPECT_EQ(first.frame_count, static_cast<int>(job->frames().size()));
  EXPECT_EQ(first.host, "sender-pc");
  EXPECT_EQ(first.outcome, "queued");
  EXPECT_EQ(first.requested_at, queued.time);

  ProgressEvent sending = event(Kind::Transmitting, 0, 1, job.get());
  sending.time = queued.time + std::chrono::milliseconds(30);
  rows = record.on_event(*job, sending);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(command_in(rows[0]).id, first.id);
  EXPECT_EQ(command_in(rows[0]).outcome, "transmitting");
  const store::FrameAttemptRow attempt1 = attempt_in(rows[1]);
  EXPECT_EQ(attempt1.command_id, job->id());
  EXPECT_EQ(attempt1.run_id, "run-1");
  EXPECT_EQ(attempt1.position, 0);
  EXPECT_EQ(attempt1.attempt, 1);
  EXPECT_EQ(attempt1.frame, job->frames()[0]->bits.decimal());
  EXPECT_EQ(attempt1.frame_width, job->frames()[0]->bit_count);
  EXPECT_EQ(attempt1.tones_hz, job->frames()[0]->tones_hz);
  EXPECT_EQ(attempt1.chord_started_at, sending.time);
  EXPECT_FALSE(attempt1.answer);

  ProgressEvent silence = event(Kind::NoAnswer, 0, 1);
  silence.chord_ended_at = sending.time + std::chrono::milliseconds(400);
  rows = record.on_event(*job, silence);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(attempt_in(rows[0]).id, attempt1.id);
  EXPECT_EQ(attempt_in(rows[0]).answer, "none");
  EXPECT_EQ(attempt_in(rows[0]).chord_ended_at, silence.chord_ended_at);
  EXPECT_FALSE(attempt_in(rows[0]).answered_at);

  rows = record.on_event(*job, event(Kind::Retransmitting, 0, 2, job.get()));
  ASSERT_EQ(rows.size(), 1u);  // the command is already transmitting
  const store::FrameAttemptRow attempt2 = attempt_in(rows[0]);
  EXPECT_NE(attempt2.id, attempt1.id);
  EXPECT_EQ(attempt2.attempt, 2);

  ProgressEvent ack = event(Kind::Ack, 0, 2);
  ack.chord_ended_at = store::WallClock::now();
  ack.answered_at = *ack.chord_ended_at + std::chrono::milliseconds(150);
  rows = record.on_event(*job, ack);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(attempt_in(rows[0]).id, attempt2.id);
  EXPECT_EQ(attempt_in(rows[0]).answer, "ack");
  EXPECT_EQ(attempt_in(rows[0]).answered_at, ack.answered_at);

  EXPECT_TRUE(record.on_event(*job, event(Kind::AwaitingDecision, 0, 2)).empty());

  ProgressEvent done = event(Kind::Confirmed);
  done.outcome = Outcome::Confirmed;
  rows = record.on_event(*job, done);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(command_in(rows[0]).id, first.id);
  EXPECT_EQ(command_in(rows[0]).outcome, "confirmed");
  EXPECT_EQ(command_in(rows[0]).finished_at, done.time);
  EXPECT_EQ(command_in(rows[0]).requested_at, first.requested_at);
}

TEST(StoreRecorder, HowACommandEndedIsItsOutcomeWithTheReason) {
  for (const auto& [outcome, name] : std::vector<std::pair<Outcome, std::string>>{{Outcome::Failed, "failed"},
                                                                                  {Outcome::Cancelled, "cancelled"},
                                                                                  {Outcome::Unavailable, "failed"},
                                                                                  {Outcome::Continued, "continued"}}) {
    const auto job = drive_job(fast_profile());
    TransmissionRecord record("h");
    record.on_event(*job, event(Kind::Queued));
    ProgressEvent last = event(outcome == Outcome::Continued ? Kind::Continued : Kind::Failed);
    last.outcome = outcome;
    last.detail = "why";
    const auto rows = record.on_event(*job, last);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(command_in(rows[0]).outcome, name);
    EXPECT_EQ(command_in(rows[0]).detail, "why");
    EXPECT_EQ(command_in(rows[0]).profile, "fast");
    EXPECT_EQ(command_in(rows[0]).id, job->id());
  }
}

TEST(StoreRecorder, AnAnswerWithoutAChordWritesNothing) {
  const auto job = drive_job(seed_profile());
  TransmissionRecord record("h");
  record.on_event(*job, event(Kind::Queued));
  EXPECT_TRUE(record.on_event(*job, event(Kind::Ack, 0, 1)).empty());
}

TEST(StoreRecorder, AJointRenewalIsOneRowNamingItsRobotsInItsParametersAndEndsSent) {
  link::TransmitFrame frame;
  frame.bits = 12345;
  frame.bit_count = 80;
  frame.renewal = true;
  frame.authenticated = true;
  const Job job(link_of(profile_by_name("fast")), frame, {{0, "robot1", 1}, {2, "robot3", 3}}, "run-1");
  ASSERT_TRUE(job.renewal());
  EXPECT_EQ(job.description(), "renewal of robot1, robot3");
  TransmissionRecord record("sender-pc");
  const auto queued = record.on_event(job, event(Kind::Queued));
  ASSERT_EQ(queued.size(), 1u);
  const store::CommandRow& row = command_in(queued[0]);
  EXPECT_EQ(row.kind, "renewal");
  EXPECT_FALSE(row.robot) << "several robots'";
  EXPECT_FALSE(row.robot_address);
  EXPECT_FALSE(row.every_robot);
  EXPECT_EQ(row.parameters["robots"], nlohmann::json({"robot1", "robot3"}));
  EXPECT_EQ(row.parameters["addresses"], nlohmann::json({1, 3}));
  const auto on_air = record.on_event(job, event(Kind::Transmitting, 0, 1, &job));
  ASSERT_EQ(on_air.size(), 2u);
  EXPECT_EQ(attempt_in(on_air[1]).frame, "12345");
  ProgressEvent sent = event(Kind::Sent, 0, 1, &job);
  sent.outcome = Outcome::Sent;
  const auto ended = record.on_event(job, sent);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(command_in(ended[0]).outcome, "sent");
}

// Listen before talk (migration 014): a WaitingForAir event writes nothing; the attempt's row,
// when its chord starts, keeps how long it waited and why, and 0 for one that went at once.
TEST(StoreRecorder, AWaitForTheAirIsKeptWithTheAttemptThatWaited) {
  const auto job = drive_job(fast_profile());
  TransmissionRecord record("sender-pc");
  record.on_event(*job, event(Kind::Queued));
  ProgressEvent waiting = event(Kind::WaitingForAir, 0, 1, job.get());
  waiting.air_wait_reason = "sound 14 dB over the room's floor";
  EXPECT_TRUE(record.on_event(*job, waiting).empty());

  ProgressEvent sending = event(Kind::Transmitting, 0, 1, job.get());
  sending.air_wait_ms = 1234.5;
  sending.air_wait_reason = waiting.air_wait_reason;
  auto rows = record.on_event(*job, sending);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(attempt_in(rows[1]).air_wait_ms, 1234.5);
  EXPECT_EQ(attempt_in(rows[1]).air_wait_reason, "sound 14 dB over the room's floor");
  EXPECT_EQ(store::to_json(attempt_in(rows[1]))["air_wait_ms"], 1234.5);

  record.on_event(*job, event(Kind::NoAnswer, 0, 1));
  rows = record.on_event(*job, event(Kind::Retransmitting, 0, 2, job.get()));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(attempt_in(rows[0]).air_wait_ms, 0);
  EXPECT_FALSE(attempt_in(rows[0]).air_wait_reason);
}
