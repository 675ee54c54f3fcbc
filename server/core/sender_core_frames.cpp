// SenderCore: one job's frames on the air, each through a retry controller (seed Fig. 8). A
// frame waits for the air (listen before talk), plays, and waits for its answer; after the
// profile's retransmissions the command's policy decides (ask the caller, continue, fail).
// Frames no robot answers (a stop for every robot, a joint renewal) play once each.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

#include "reliability/renewal_frame.h"
#include "sender_core.h"

namespace dtmf::server {

namespace {
using Kind = ProgressEvent::Kind;
using reliability::RetryState;

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

reliability::RetryPolicy retry_policy(const Job& job) {
  const LinkTiming& timing = job.profile().timing;
  const bool once = job.policy() == Policy::Live || job.policy() == Policy::Unanswered;
  return {once ? 0 : timing.auto_retransmissions, timing.ack_timeout_ms};
}

std::string ended_unanswered(const Job& job) {
  return job.renewal()
             ? "played; no robot answers a joint renewal, each that heard it holds its velocity for a lease more"
             : std::to_string(job.frame_count()) +
                   " copies played; no robot answers a stop for every robot, each that heard one stopped";
}
}  // namespace

SenderCore::MaybeStep SenderCore::next_frame(Sending& s, double now_ms) {
  Job& job = *s.job;
  if (s.ending(stopping_)) {  // by its caller, a Stop that overtook it, or the shutdown: not one more frame
    end_cancelled(s, now_ms);
    return std::nullopt;
  }
  if (!s.retry || s.retry->finished()) {
    if (s.retry && s.retry->state() == RetryState::Failed) {
      end(s, Outcome::Failed,
          "frame " + std::to_string(s.index + 1) + " of " + std::to_string(job.frame_count()) +
              " was not confirmed by the robot",
          now_ms);
      return std::nullopt;
    }
    s.continued = s.continued || (s.retry && s.retry->state() == RetryState::Continued);
    if (++s.index >= job.frame_count()) {
      // Allowed, but never to be taken for a keyed confirmation (--allow-unauthenticated-commands).
      const bool untagged = job.link().keyed() && !job.frames().empty() && !job.frames().back()->authenticated;
      if (job.policy() == Policy::Unanswered)
        end(s, Outcome::Sent, ended_unanswered(job), now_ms);
      else
        end(s, s.continued ? Outcome::Continued : Outcome::Confirmed,
            untagged ? "unauthenticated: the robot's ACK carries no tag, and anyone within earshot can play one" : "",
            now_ms);
      return std::nullopt;
    }
    s.retry.emplace(retry_policy(job));
    s.retry->start();
  }
  switch (s.retry->state()) {
    case RetryState::AwaitingAnswer:
      s.phase = Sending::Phase::Answer;
      return std::nullopt;
    case RetryState::AwaitingDecision:
      s.phase = Sending::Phase::Decision;
      return std::nullopt;
    default:
      break;
  }
  // A command's later frames and retransmissions may keep the air longer than a lease: the
  // renewals that fall due meanwhile go between them (a renewal carries no command). Not
  // between the seed's word frames: its robots hear a command in several frames.
  const bool later = s.index > 0 || s.retry->attempt() > 0;
  if (later && !s.renewed_before && !job.renewal() && !job.frames().front()->word) {
    const std::vector<RobotIndex> due = renewals_.due(now_ms, reliability::kRenewalSlots);
    s.renewed_before = true;
    if (!due.empty() && start_renewal(due, now_ms)) return WaitUntil{now_ms};  // `s` waits behind it
  }
  s.phase = Sending::Phase::Air;
  return std::nullopt;
}

SenderCore::MaybeStep SenderCore::play(Sending& s, double now_ms) {
  Job& job = *s.job;
  const link::TransmitFrame& frame = *job.frames().at(static_cast<std::size_t>(s.index));
  s.chord_start_ms = now_ms;
  s.renewed_before = false;
  s.retry->on_transmit_started(now_ms);
  if (!frame.broadcast) frame_started(job, now_ms);  // every frame for a robot renews its lease
  ProgressEvent sending = attempt_event(s, s.retry->attempt() == 1 ? Kind::Transmitting : Kind::Retransmitting);
  tell_air_wait(job, sending);
  emit(s.job, sending, now_ms);
  if (frame.counter) {
    // The MAC's input but the key and payload, before the frame sounds (stderr is
    // unbuffered): a record that shows no counter goes on air for two frames, even
    // across a kill -9 (tests/e2e/authenticated_e2e_test.cpp).
    const link::LinkOptions& o = job.link().options();
    spdlog::info("{} (command {}, frame {}): on air: {} frame, key {}, robot {}, counter {}, attempt {}",
                 job.description(), job.id(), s.index, frame.synchronisation ? "synchronisation" : "command",
                 o.key ? o.key->id_hex() : "-", o.address, *frame.counter, s.retry->attempt());
  }
  s.phase = Sending::Phase::Playing;
  return Play{s.job, job.frames()[static_cast<std::size_t>(s.index)], now_ms};
}

SenderCore::MaybeStep SenderCore::playing(Sending& s, double now_ms) {
  const link::TransmitFrame& frame = *s.job->frames().at(static_cast<std::size_t>(s.index));
  const double end_ms = s.chord_start_ms + frame.tone_ms;
  if (now_ms < end_ms) return WaitUntil{end_ms};
  // Our frame ended: the microphone listens while we wait for its answer.
  carrier_.frame_ended(now_ms);
  s.chord_end_ms = now_ms;
  channel_free_ms_ = s.chord_start_ms + frame.next_frame_after_ms;
  if (s.job->policy() == Policy::Unanswered) {
    exchange_ended(now_ms);  // no answer comes
    s.retry.reset();
    s.phase = Sending::Phase::NextFrame;
    return std::nullopt;
  }
  s.answer_until_ms = answer_wait_end_ms(*s.job, s.chord_start_ms + frame.tone_ms, *s.retry->deadline_ms());
  s.phase = Sending::Phase::Answer;
  return std::nullopt;
}

SenderCore::MaybeStep SenderCore::await_answer(Sending& s, double now_ms) {
  const std::optional<HeardReply> reply = take_reply(s);
  // A Stop overtakes the wait; so does the shutdown.
  if (!reply && !stopping_ && !stop_waiting_ && now_ms < s.answer_until_ms) return WaitUntil{s.answer_until_ms};
  answered(s, reply, now_ms);
  s.phase = Sending::Phase::NextFrame;
  return std::nullopt;
}

void SenderCore::answered(Sending& s, const std::optional<HeardReply>& reply, double now_ms) {
  Job& job = *s.job;
  reliability::RetryController& retry = *s.retry;
  const link::TransmitFrame& frame = *job.frames().at(static_cast<std::size_t>(s.index));
  const double frame_end_ms = s.chord_start_ms + frame.tone_ms;
  ProgressEvent answer = attempt_event(s, Kind::NoAnswer);
  answer.chord_ended_ms = s.chord_end_ms;
  // Where our robot's answer sounded, or would have: what the microphone heard there is ours.
  const double answer_ms = job.profile().timing.ack_ms;
  Robot& robot = robots_[robot_of(job.link())];
  if (reply) {
    const auto kind = reply->answer.answer.ack ? reliability::Answer::Ack : reliability::Answer::Nack;
    retry.on_answer(kind, reply->at_ms);
    answer.kind = kind == reliability::Answer::Ack ? Kind::Ack : Kind::Nack;
    if (kind == reliability::Answer::Ack) job.link().confirmed(frame);
    robot.last_answered_ms = reply->at_ms;
    answer.response_time_ms = retry.response_time_ms();
    answer.answered_ms = reply->at_ms;
    robot.answer_delay_ms = std::max(0.0, reply->at_ms - answer_ms - frame_end_ms);
  } else {
    retry.on_tick(std::max(now_ms, *retry.deadline_ms()));
  }
  const LinkTiming& timing = job.profile().timing;
  const reliability::AirSpan answer_span = reliability::own_answer_span(
      frame_end_ms, robot.answer_delay_ms, timing.ack_timeout_ms - timing.chord_ms, answer_ms);
  exchange_ended(now_ms, answer_span, !reply || !reply->answer.answer.ack);
  emit(s.job, answer, now_ms);
}

SenderCore::MaybeStep SenderCore::await_decision(Sending& s, double now_ms) {
  Job& job = *s.job;
  std::optional<reliability::Decision> decision;
  if (job.policy() == Policy::Continue || job.policy() == Policy::Live) {
    decision = reliability::Decision::Continue;
  } else if (job.policy() == Policy::Fail) {
    decision = reliability::Decision::GiveUp;
  } else if (!s.decision_until_ms) {
    ProgressEvent ask = attempt_event(s, Kind::AwaitingDecision);
    ask.detail = "frame " + std::to_string(s.index + 1) + " unconfirmed after " + std::to_string(s.retry->attempt()) +
                 " transmissions: call Decide(command_id, CONTINUE | RETRANSMIT | ABORT)";
    job.open_decision();
    emit(s.job, ask, now_ms);
    s.decision_until_ms = now_ms + static_cast<double>(job.decision_timeout().count());
    return WaitUntil{*s.decision_until_ms};
  } else {
    decision = job.take_decision();
    if (!decision) {
      const bool cancelled = job.cancelled() || stopping_;
      if (!cancelled && now_ms < *s.decision_until_ms) return WaitUntil{*s.decision_until_ms};
      if (cancelled)
        end_cancelled(s, now_ms);
      else
        end(s, Outcome::Failed, "no decision within the decision timeout", now_ms);
      return std::nullopt;
    }
  }
  s.decision_until_ms.reset();
  s.retry->on_decision(*decision);
  s.phase = Sending::Phase::NextFrame;
  return std::nullopt;
}

}  // namespace dtmf::server
