// Transmitter::send: one command's frames through the retry controller (seed Fig. 8).
#include <spdlog/spdlog.h>

#include "transmitter.h"

namespace dtmf::server {

namespace {
using Kind = ProgressEvent::Kind;
using reliability::RetryState;

}  // namespace

store::WallTime Transmitter::wall(double steady_ms) const {
  const auto steady = epoch_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double, std::milli>(steady_ms));
  return store::WallClock::now() +
         std::chrono::duration_cast<store::WallClock::duration>(steady - std::chrono::steady_clock::now());
}

store::FrameAttemptRow Transmitter::attempt_row(const Job& job, int frame_index, int attempt, double start_ms) const {
  const link::TransmitFrame& f = job.frames()[static_cast<std::size_t>(frame_index)];
  store::FrameAttemptRow row;
  row.run_id = job.run_id();
  row.command_id = job.id();
  row.position = frame_index;
  row.attempt = attempt;
  if (f.word) row.word = *f.word;
  row.frame = f.bits;
  row.frame_width = f.bit_count;
  row.tones_hz = f.tones_hz;
  row.chord_started_at = wall(start_ms);
  return row;
}

void Transmitter::send(Job& job) {
  const LinkProfile& profile = job.profile();
  const reliability::RetryPolicy policy{profile.timing.auto_retransmissions, profile.timing.ack_timeout_ms};
  bool continued = false;
  job.log_row().outcome = "transmitting";
  store_.write(job.log_row());
  const auto end = [&](Outcome outcome, const std::string& detail) {
    ProgressEvent last{outcome == Outcome::Confirmed   ? Kind::Confirmed
                       : outcome == Outcome::Continued ? Kind::Continued
                                                       : Kind::Failed};
    last.detail = detail;
    job.emit(last);
    store::CommandRow& row = job.log_row();
    row.finished_at = store::WallClock::now();
    row.outcome = outcome_name(outcome);
    row.detail = detail;
    store_.write(row);
    job.finish(outcome, detail);
    spdlog::info("{}: {}{}", job.description(), outcome_name(outcome), detail.empty() ? "" : " (" + detail + ")");
  };

  for (int index = 0; index < static_cast<int>(job.frames().size()); ++index) {
    const link::TransmitFrame& frame = job.frames()[static_cast<std::size_t>(index)];
    reliability::RetryController retry(policy);
    retry.start();
    std::optional<store::FrameAttemptRow> attempt;
    double chord_start = 0;
    while (!retry.finished()) {
      switch (retry.state()) {
        case RetryState::TransmitPending: {
          if (job.cancelled()) {
            bool stopping;
            {
              std::lock_guard lock(mutex_);
              stopping = stopping_;
            }
            end(stopping ? Outcome::Unavailable : Outcome::Cancelled,
                stopping ? "the server is shutting down" : "cancelled by the caller");
            return;
          }
          // One chord on air at a time, with the profile's silence between chords.
          while (now_ms() < channel_free_ms_) {
            std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(channel_free_ms_ - now_ms()));
          }
          ProgressEvent sending{retry.attempt() == 1 ? Kind::Transmitting : Kind::Retransmitting};
          sending.frame_index = index;
          sending.attempt = retry.attempt();
          job.emit(sending);
          chord_start = now_ms();
          retry.on_transmit_started(chord_start);
          attempt = attempt_row(job, index, retry.attempt(), chord_start);
          store_.write(*attempt);
          try {
            play(frame, chord_start);
          } catch (const std::exception& e) {
            {
              std::lock_guard lock(mutex_);
              unavailable_ = std::string("the loudspeaker failed: ") + e.what();
            }
            spdlog::error("{}", unavailable_);
            end(Outcome::Unavailable, unavailable_);
            return;
          }
          attempt->chord_ended_at = wall(now_ms());
          store_.write(*attempt);
          channel_free_ms_ = chord_start + frame.tone_ms + profile.timing.gap_ms;
          break;
        }
        case RetryState::AwaitingAnswer: {
          const auto reply = wait_reply(job.link(), frame, chord_start, *retry.deadline_ms());
          ProgressEvent answer{Kind::NoAnswer};
          answer.frame_index = index;
          answer.attempt = retry.attempt();
          if (reply) {
            const auto kind = reply->answer.answer.ack ? reliability::Answer::Ack : reliability::Answer::Nack;
            retry.on_answer(kind, reply->steady_ms);
            answer.kind = kind == reliability::Answer::Ack ? Kind::Ack : Kind::Nack;
            answer.response_time_ms = retry.response_time_ms();
            attempt->answer = kind == reliability::Answer::Ack ? "ack" : "nack";
            attempt->answered_at = wall(reply->steady_ms);
          } else {
            retry.on_tick(std::max(now_ms(), *retry.deadline_ms()));
            attempt->answer = "none";
          }
          store_.write(*attempt);
          job.emit(answer);
          break;
        }
        case RetryState::AwaitingDecision: {
          std::optional<reliability::Decision> decision;
          if (job.policy() == Policy::Continue)
            decision = reliability::Decision::Continue;
          else if (job.policy() == Policy::Fail)
            decision = reliability::Decision::GiveUp;
          else {
            ProgressEvent ask{Kind::AwaitingDecision};
            ask.frame_index = index;
            ask.attempt = retry.attempt();
            ask.detail = "frame " + std::to_string(index + 1) + " unconfirmed after " +
                         std::to_string(retry.attempt()) +
                         " transmissions: call Decide(command_id, CONTINUE | RETRANSMIT | ABORT)";
            job.emit(ask);
            decision = job.await_decision();
            if (!decision) {
              end(job.cancelled() ? Outcome::Cancelled : Outcome::Failed,
                  job.cancelled() ? "cancelled by the caller" : "no decision within the decision timeout");
              return;
            }
          }
          retry.on_decision(*decision);
          break;
        }
        default:
          break;
      }
    }
    if (retry.state() == RetryState::Failed) {
      end(Outcome::Failed, "frame " + std::to_string(index + 1) + " of " + std::to_string(job.frames().size()) +
                               " was not confirmed by the robot");
      return;
    }
    continued = continued || retry.state() == RetryState::Continued;
  }
  end(continued ? Outcome::Continued : Outcome::Confirmed, "");
}

}  // namespace dtmf::server
