// Transmitter::send: one command's frames through the retry controller (seed Fig. 8).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "transmitter.h"

namespace dtmf::server {

namespace {
using Kind = ProgressEvent::Kind;
using reliability::RetryState;

// Why a job ended cancelled: its caller, or a Stop that overtook it.
std::string cancelled_detail(Job& job) {
  return job.overtaken() ? "overtaken by a Stop, which went on the air at once: its answer was not awaited (the "
                           "robot may have executed it); send it again after the stop"
                         : "cancelled by the caller";
}

// How long the attempt `sending` starts waited for the air, and why: on its event, for the
// operator and the record; and said aloud when the command's bound sent it into the sound.
void tell_air_wait(Job& job, ProgressEvent& sending) {
  const reliability::AirWait& wait = job.air_wait();
  if (wait.last_ms <= 0) return;
  sending.air_wait_ms = wait.last_ms;
  sending.air_wait_reason = reliability::air_wait_text(wait.reason);
  if (wait.held_ms < reliability::kMaxDeferToUnknownMs) return;
  sending.air_wait_bounded = true;
  char text[160];
  std::snprintf(text, sizeof text,
                "the air held this command %.1f s, the most a command waits: it goes out into the sound",
                wait.held_ms / 1000);
  sending.detail = text;
  spdlog::warn("{} (command {}): {} ({})", job.description(), job.id(), text, sending.air_wait_reason);
}

}  // namespace

store::WallTime Transmitter::wall(double steady_ms) const {
  const auto steady = epoch_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double, std::milli>(steady_ms));
  return store::WallClock::now() +
         std::chrono::duration_cast<store::WallClock::duration>(steady - std::chrono::steady_clock::now());
}

void Transmitter::emit(Job& job, ProgressEvent event) {
  observer_.observe(job, event);
  publish_air(job, event);
  job.emit(std::move(event));
}

void Transmitter::end(Job& job, Outcome outcome, const std::string& detail) {
  ProgressEvent last{outcome == Outcome::Confirmed   ? Kind::Confirmed
                     : outcome == Outcome::Continued ? Kind::Continued
                     : outcome == Outcome::Sent      ? Kind::Sent
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

struct Transmitter::FrameAttempt {
  int index;
  std::shared_ptr<const link::TransmitFrame> frame;
  reliability::RetryController retry;
  double chord_start = 0;
  std::optional<store::WallTime> chord_end;

  // An event about this frame's current attempt.
  ProgressEvent event(Kind kind, const Job& job) const {
    ProgressEvent e{kind};
    e.frame = frame;
    e.frame_count = job.frame_count();
    e.frame_index = index;
    e.attempt = retry.attempt();
    return e;
  }
};

void Transmitter::end_cancelled(Job& job) {
  bool stopping;
  {
    std::lock_guard lock(mutex_);
    stopping = stopping_;
  }
  end(job, stopping ? Outcome::Unavailable : Outcome::Cancelled,
      stopping ? "the server is shutting down" : cancelled_detail(job));
}

void Transmitter::send_unanswered(Job& job) {
  for (int index = 0; index < job.frame_count(); ++index) {
    FrameAttempt attempt{index, job.frames()[static_cast<std::size_t>(index)],
                         reliability::RetryController({0, job.profile().timing.ack_timeout_ms}), 0, std::nullopt};
    attempt.retry.start();
    if (!transmit(job, attempt)) return;
    exchange_ended();  // no answer comes
  }
  end(job, Outcome::Sent,
      job.renewal() ? "played; no robot answers a joint renewal, each that heard it holds its velocity for a lease more"
                    : std::to_string(job.frame_count()) +
                          " copies played; no robot answers a stop for every robot, each that heard one stopped");
}

void Transmitter::send(Job& job) {
  if (job.policy() == Policy::Unanswered) return send_unanswered(job);
  const LinkProfile& profile = job.profile();
  const int retransmissions = job.policy() == Policy::Live ? 0 : profile.timing.auto_retransmissions;
  const reliability::RetryPolicy policy{retransmissions, profile.timing.ack_timeout_ms};
  bool continued = false;
  for (int index = 0; index < job.frame_count(); ++index) {
    FrameAttempt attempt{index, job.frames()[static_cast<std::size_t>(index)], reliability::RetryController(policy), 0,
                         std::nullopt};
    attempt.retry.start();
    while (!attempt.retry.finished()) {
      if (job.cancelled()) {  // by its caller, a Stop that overtook it, or the shutdown: not one more frame
        end_cancelled(job);
        return;
      }
      switch (attempt.retry.state()) {
        case RetryState::TransmitPending:
          if (!transmit(job, attempt)) return;
          break;
        case RetryState::AwaitingAnswer:
          await_answer(job, attempt);
          break;
        case RetryState::AwaitingDecision:
          if (!decide(job, attempt)) return;
          break;
        default:
          break;
      }
    }
    if (attempt.retry.state() == RetryState::Failed) {
      end(job, Outcome::Failed,
          "frame " + std::to_string(index + 1) + " of " + std::to_string(job.frame_count()) +
              " was not confirmed by the robot");
      return;
    }
    continued = continued || attempt.retry.state() == RetryState::Continued;
  }
  // Allowed, but never to be taken for a keyed confirmation (--allow-unauthenticated-commands).
  const bool untagged = job.link().keyed() && !job.frames().empty() && !job.frames().back()->authenticated;
  end(job, continued ? Outcome::Continued : Outcome::Confirmed,
      untagged ? "unauthenticated: the robot's ACK carries no tag, and anyone within earshot can play one" : "");
}

bool Transmitter::transmit(Job& job, FrameAttempt& attempt) {
  // A command's later frames and retransmissions may keep the air longer than a lease: the
  // renewals that fall due meanwhile go between them (a renewal carries no command).
  if (attempt.index > 0 || attempt.chord_start != 0) renew_between_frames(job);
  // One chord on air at a time, with the profile's silence between chords, and none into
  // another sender's exchange.
  if (job.cancelled() || !wait_for_air(job, attempt.event(Kind::WaitingForAir, job))) {
    end_cancelled(job);
    return false;
  }
  const link::TransmitFrame& frame = *attempt.frame;
  reliability::RetryController& retry = attempt.retry;
  attempt.chord_start = now_ms();
  retry.on_transmit_started(attempt.chord_start);
  if (!frame.broadcast) {  // every frame for a robot renews its lease
    std::lock_guard lock(mutex_);
    if (job.renewal()) {
      for (const Job::Renewed& r : job.renewed()) {
        renewals_.frame_started(r.index, attempt.chord_start);
        robots_[r.index].renewed_ms = attempt.chord_start;
        robots_[r.index].frame_started_ms = attempt.chord_start;
      }
    } else {
      const RobotIndex robot = robot_of(job.link());
      renewals_.frame_started(robot, attempt.chord_start);
      robots_[robot].frame_started_ms = attempt.chord_start;
    }
  }
  ProgressEvent sending = attempt.event(retry.attempt() == 1 ? Kind::Transmitting : Kind::Retransmitting, job);
  sending.time = wall(attempt.chord_start);
  tell_air_wait(job, sending);
  emit(job, sending);
  if (frame.counter) {
    // The MAC's input but the key and payload, before the frame sounds (stderr is
    // unbuffered): a record that shows no counter goes on air for two frames, even
    // across a kill -9 (tests/e2e/authenticated_e2e_test.cpp).
    const link::LinkOptions& o = job.link().options();
    spdlog::info("{} (command {}, frame {}): on air: {} frame, key {}, robot {}, counter {}, attempt {}",
                 job.description(), job.id(), attempt.index, frame.synchronisation ? "synchronisation" : "command",
                 o.key ? o.key->id_hex() : "-", o.address, *frame.counter, retry.attempt());
  }
  try {
    play(frame, attempt.chord_start);
  } catch (const std::exception& e) {
    {
      std::lock_guard lock(mutex_);
      unavailable_ = std::string("the loudspeaker failed: ") + e.what();
    }
    spdlog::error("{}", unavailable_);
    exchange_ended();
    end(job, Outcome::Unavailable, unavailable_);
    return false;
  }
  frame_ended();
  attempt.chord_end = wall(now_ms());
  channel_free_ms_ = attempt.chord_start + frame.next_frame_after_ms;
  return true;
}

void Transmitter::await_answer(Job& job, FrameAttempt& attempt) {
  reliability::RetryController& retry = attempt.retry;
  const double frame_end_ms = attempt.chord_start + attempt.frame->tone_ms;
  const auto reply = wait_reply(job.link(), *attempt.frame, attempt.chord_start,
                                answer_wait_end_ms(job, frame_end_ms, *retry.deadline_ms()));
  ProgressEvent answer = attempt.event(Kind::NoAnswer, job);
  answer.chord_ended_at = attempt.chord_end;
  // Where our robot's answer sounded, or would have: what the microphone heard there is ours.
  const double answer_ms = job.profile().timing.ack_ms;
  std::optional<double>& answer_delay_ms = robots_[robot_of(job.link())].answer_delay_ms;
  if (reply) {
    const auto kind = reply->answer.answer.ack ? reliability::Answer::Ack : reliability::Answer::Nack;
    retry.on_answer(kind, reply->steady_ms);
    answer.kind = kind == reliability::Answer::Ack ? Kind::Ack : Kind::Nack;
    if (kind == reliability::Answer::Ack) job.link().confirmed(*attempt.frame);
    {
      std::lock_guard lock(mutex_);
      robots_[robot_of(job.link())].last_answered_ms = reply->steady_ms;
    }
    answer.response_time_ms = retry.response_time_ms();
    answer.answered_at = wall(reply->steady_ms);
    answer_delay_ms = std::max(0.0, reply->steady_ms - answer_ms - frame_end_ms);
  } else {
    retry.on_tick(std::max(now_ms(), *retry.deadline_ms()));
  }
  const LinkTiming& timing = job.profile().timing;
  const reliability::AirSpan answer_span =
      reliability::own_answer_span(frame_end_ms, answer_delay_ms, timing.ack_timeout_ms - timing.chord_ms, answer_ms);
  exchange_ended(answer_span, !reply || !reply->answer.answer.ack);
  emit(job, answer);
}

bool Transmitter::decide(Job& job, FrameAttempt& attempt) {
  std::optional<reliability::Decision> decision;
  if (job.policy() == Policy::Continue || job.policy() == Policy::Live) {
    decision = reliability::Decision::Continue;
  } else if (job.policy() == Policy::Fail) {
    decision = reliability::Decision::GiveUp;
  } else {
    ProgressEvent ask = attempt.event(Kind::AwaitingDecision, job);
    ask.detail = "frame " + std::to_string(attempt.index + 1) + " unconfirmed after " +
                 std::to_string(attempt.retry.attempt()) +
                 " transmissions: call Decide(command_id, CONTINUE | RETRANSMIT | ABORT)";
    job.open_decision();
    emit(job, ask);
    decision = job.await_decision();
    if (!decision) {
      end(job, job.cancelled() ? Outcome::Cancelled : Outcome::Failed,
          job.cancelled() ? cancelled_detail(job) : "no decision within the decision timeout");
      return false;
    }
  }
  attempt.retry.on_decision(*decision);
  return true;
}

}  // namespace dtmf::server
