#include "agent.h"

#include <spdlog/spdlog.h>

#include "command/word_codec.h"

namespace dtmf::agent {

Agent::Agent(AgentOptions options, ReplyPlayer& replies, std::vector<CmdVelOutput*> outputs, store::Store& store,
             Timeline& timeline)
    : options_(std::move(options)),
      replies_(replies),
      outputs_(std::move(outputs)),
      store_(store),
      timeline_(timeline),
      receiver_(*options_.profile),
      provider_(options_.model, options_.continuous_limit_s) {}

double Agent::audio_ms() const { return static_cast<double>(samples_) * 1000.0 / options_.profile->sample_rate_hz; }

void Agent::process(std::span<const float> samples, double queued_ms) {
  samples_ += static_cast<long long>(samples.size());
  timeline_.block_read(audio_ms(), queued_ms);
  // Frames first: a command heard in this block takes effect from its own time, so the
  // publish ticks of this block already carry it.
  for (const link::ReceivedFrame& frame : receiver_.feed(samples)) on_frame(frame);
  publish_until(audio_ms());
}

void Agent::on_frame(const link::ReceivedFrame& frame) {
  ++frames_heard_;
  const signal::Reply reply = frame.crc_ok ? signal::Reply::Ack : signal::Reply::Nack;
  replies_.play(reply, frame.heard_ms);

  store::ReceptionRow row;
  row.host = options_.host;
  row.profile = options_.profile->name;
  row.started_at = timeline_.wall(frame.start_ms);
  row.heard_at = timeline_.wall(frame.heard_ms);
  row.frame = frame.frame;
  row.crc_ok = frame.crc_ok;
  row.reply = frame.crc_ok ? "ack" : "nack";

  const std::string bits = reliability::bit_string(frame.frame);
  if (!frame.crc_ok) {
    spdlog::warn("t={:.3f}s frame {} failed the CRC: NACK", frame.heard_ms / 1000.0, bits);
    store_.write(row);
    if (options_.on_frame_heard) options_.on_frame_heard(frame);
    return;
  }
  const command::ReceiverEvent& event = *frame.event;
  row.word = reliability::frame_word(frame.frame);
  row.event = command::event_kind_name(event.kind);
  row.command_state = command::state_name(event.state_after);
  std::string what = row.event;
  if (event.kind == command::ReceiverEvent::Kind::ModeSelected) what += " " + command::mode_name(*event.mode);
  if (event.kind == command::ReceiverEvent::Kind::Ignored) what += " (" + event.reason + ")";
  if (event.command) {
    // Catch up the publish ticks before the command, so it takes effect from its own time.
    publish_until(frame.heard_ms, false);
    provider_.apply(*event.command, frame.heard_ms / 1000.0);
    row.command = command::describe(*event.command);
    row.linear_mps = provider_.velocity().linear_mps;
    row.angular_rps = provider_.velocity().angular_rps;
    what = "command " + row.command;
  }
  spdlog::info("t={:.3f}s frame {} word {}: ACK, {}", frame.heard_ms / 1000.0, bits, *row.word, what);
  store_.write(row);
  if (options_.on_frame_heard) options_.on_frame_heard(frame);
}

void Agent::publish(const Velocity& velocity, double audio_ms) {
  const auto stamp = timeline_.wall(audio_ms);
  for (CmdVelOutput* output : outputs_) output->publish(velocity, audio_ms, stamp);
}

void Agent::publish_until(double audio_ms, bool inclusive) {
  const double period_ms = 1000.0 / options_.publish_rate_hz;
  while (next_publish_ms_ < audio_ms || (inclusive && next_publish_ms_ == audio_ms)) {
    const Velocity velocity = provider_.update(next_publish_ms_ / 1000.0);
    if (auto reason = provider_.take_stop_reason()) spdlog::info("t={:.3f}s stop: {}", next_publish_ms_ / 1000.0, *reason);
    publish(velocity, next_publish_ms_);
    next_publish_ms_ += period_ms;
  }
}

void Agent::finish(const std::function<void()>& after_block) {
  // A timed motion still running at the end of the recording runs out as if in silence.
  const int block = options_.profile->hop_samples();
  const std::vector<float> silence(static_cast<std::size_t>(block), 0.0f);
  while (provider_.state() == MotionState::Duration) {
    process(silence);
    if (after_block) after_block();
  }
  stop_now("end of the audio input");
}

void Agent::stop_now(const std::string& why) {
  if (provider_.state() != MotionState::Idle) spdlog::info("stopping the robot: {}", why);
  provider_.stop();
  publish(Velocity{}, audio_ms());
}

}  // namespace dtmf::agent
