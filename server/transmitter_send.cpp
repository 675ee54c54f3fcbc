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

void Transmitter::emit(Job& job, ProgressEvent event) {
  observer_.observe(job, event);
  job.emit(std::move(event));
}

void Transmitter::end(Job& job, Outcome outcome, const std::string& detail) {
  ProgressEvent last{outcome == Outcome::Confirmed   ? Kind::Confirmed
                     : outcome == Outcome::Continued ? Kind::Continued
                                                     : Kind::Failed};
  last.outcome = outcome;
  last.frame_count = job.frame_count();
  if (!job.frames().empty()) {
    last.frame_index = job.frame_count() - 1;
    last.frame = job.frames().back();
  }
  last.detail = detail;
  emit(job, last);
  job.finish(outcome, detail);
  spdlog::info("{}: {}{}", job.description(), outcome_name(outcome), detail.empty() ? "" : " (" + detail + ")");
}

void Transmitter::send(Job& job) {
  const LinkProfile& profile = job.profile();
  const int retransmissions = job.policy() == Policy::Live ? 0 : profile.timing.auto_retransmissions;
  const reliability::RetryPolicy policy{retransmissions, profile.timing.ack_timeout_ms};
  bool continued = false;
  for (int index = 0; index < job.frame_count(); ++index) {
    const auto& frame_ptr = job.frames()[static_cast<std::size_t>(index)];
    const link::TransmitFrame& frame = *frame_ptr;
    reliability::RetryController retry(policy);
    retry.start();
    double chord_start = 0;
    std::optional<store::WallTime> chord_end;
    while (!retry.finished()) {
      switch (retry.state()) {
        case RetryState::TransmitPending: {
          if (job.cancelled()) {
            bool stopping;
            {
              std::lock_guard lock(mutex_);
              stopping = stopping_;
            }
            end(job, stopping ? Outcome::Unavailable : Outcome::Cancelled,
                stopping ? "the server is shutting down" : "cancelled by the caller");
            return;
          }
          // One chord on air at a time, with the profile's silence between chords.
          while (now_ms() < channel_free_ms_) {
            std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(channel_free_ms_ - now_ms()));
          }
          chord_start = now_ms();
          retry.on_transmit_started(chord_start);
          ProgressEvent sending{retry.attempt() == 1 ? Kind::Transmitting : Kind::Retransmitting};
          sending.frame = frame_ptr;
          sending.frame_count = job.frame_count();
          sending.frame_index = index;
          sending.attempt = retry.attempt();
          sending.time = wall(chord_start);
          emit(job, sending);
          if (frame.counter) {
            // The MAC's input but the key and payload, before the frame sounds (stderr is
            // unbuffered): a record that shows no counter goes on air for two frames, even
            // across a kill -9 (tests/e2e/authenticated_e2e_test.cpp).
            const link::LinkOptions& o = job.link().options();
            spdlog::info("{} (command {}, frame {}): on air: {} frame, key {}, robot {}, counter {}, attempt {}",
                         job.description(), job.id(), index, frame.synchronisation ? "synchronisation" : "command",
                         o.key ? o.key->id_hex() : "-", o.address, *frame.counter, retry.attempt());
          }
          try {
            play(frame, chord_start);
          } catch (const std::exception& e) {
            {
              std::lock_guard lock(mutex_);
              unavailable_ = std::string("the loudspeaker failed: ") + e.what();
            }
            spdlog::error("{}", unavailable_);
            end(job, Outcome::Unavailable, unavailable_);
            return;
          }
          chord_end = wall(now_ms());
          channel_free_ms_ = chord_start + frame.tone_ms + profile.timing.gap_ms;
          break;
        }
        case RetryState::AwaitingAnswer: {
          const auto reply = wait_reply(job.link(), frame, chord_start, *retry.deadline_ms());
          ProgressEvent answer{Kind::NoAnswer};
          answer.frame = frame_ptr;
          answer.frame_count = job.frame_count();
          answer.frame_index = index;
          answer.attempt = retry.attempt();
          answer.chord_ended_at = chord_end;
          if (reply) {
            const auto kind = reply->answer.answer.ack ? reliability::Answer::Ack : reliability::Answer::Nack;
            retry.on_answer(kind, reply->steady_ms);
            answer.kind = kind == reliability::Answer::Ack ? Kind::Ack : Kind::Nack;
            if (kind == reliability::Answer::Ack) job.link().confirmed(frame);
            answer.response_time_ms = retry.response_time_ms();
            answer.answered_at = wall(reply->steady_ms);
          } else {
            retry.on_tick(std::max(now_ms(), *retry.deadline_ms()));
          }
          emit(job, answer);
          break;
        }
        case RetryState::AwaitingDecision: {
          std::optional<reliability::Decision> decision;
          if (job.policy() == Policy::Continue || job.policy() == Policy::Live)
            decision = reliability::Decision::Continue;
          else if (job.policy() == Policy::Fail)
            decision = reliability::Decision::GiveUp;
          else {
            ProgressEvent ask{Kind::AwaitingDecision};
            ask.frame = frame_ptr;
            ask.frame_count = job.frame_count();
            ask.frame_index = index;
            ask.attempt = retry.attempt();
            ask.detail = "frame " + std::to_string(index + 1) + " unconfirmed after " +
                         std::to_string(retry.attempt()) +
                         " transmissions: call Decide(command_id, CONTINUE | RETRANSMIT | ABORT)";
            job.open_decision();
            emit(job, ask);
            decision = job.await_decision();
            if (!decision) {
              end(job, job.cancelled() ? Outcome::Cancelled : Outcome::Failed,
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
      end(job, Outcome::Failed,
          "frame " + std::to_string(index + 1) + " of " + std::to_string(job.frame_count()) +
              " was not confirmed by the robot");
      return;
    }
    continued = continued || retry.state() == RetryState::Continued;
  }
  // Allowed, but never to be taken for a keyed confirmation (--allow-unauthenticated-commands).
  const bool untagged = keyed() && !job.frames().empty() && !job.frames().back()->authenticated;
  end(job, continued ? Outcome::Continued : Outcome::Confirmed,
      untagged ? "unauthenticated: the robot's ACK carries no tag, and anyone within earshot can play one" : "");
}

}  // namespace dtmf::server
