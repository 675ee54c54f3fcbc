#include "agent.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "command/word_codec.h"

namespace dtmf::agent {

Agent::Agent(AgentOptions options, ReplyPlayer& replies, std::vector<CmdVelOutput*> outputs, store::Store& store,
             Timeline& timeline)
    : options_(std::move(options)),
      replies_(replies),
      outputs_(std::move(outputs)),
      store_(store),
      timeline_(timeline),
      provider_(options_.model, options_.continuous_limit_s) {
  if (options_.profiles.empty()) throw std::invalid_argument("the agent needs a profile to listen with");
  sample_rate_hz_ = options_.profiles.front()->sample_rate_hz;
  block_samples_ = options_.profiles.front()->hop_samples();
  for (const LinkProfile* p : options_.profiles) {
    if (p->sample_rate_hz != sample_rate_hz_) {
      throw std::invalid_argument("profiles " + options_.profiles.front()->name + " and " + p->name +
                                  " use different sample rates and cannot share a microphone");
    }
    block_samples_ = std::min(block_samples_, p->hop_samples());
    if (p->frame_format == FrameFormat::Command48) command_paths_.emplace_back(p, std::make_unique<link::CommandFramePath>(*p));
    else word_paths_.emplace_back(p, std::make_unique<link::ReceiverPath>(*p));
  }
}

double Agent::audio_ms() const { return static_cast<double>(samples_) * 1000.0 / sample_rate_hz_; }

void Agent::process(std::span<const float> samples, double queued_ms) {
  samples_ += static_cast<long long>(samples.size());
  timeline_.block_read(audio_ms(), queued_ms);
  // Frames first: a command heard in this block takes effect from its own time, so the
  // publish ticks of this block already carry it.
  for (auto& [profile, path] : word_paths_) {
    for (const link::ReceivedFrame& frame : path->feed(samples)) on_word_frame(*profile, frame);
  }
  for (auto& [profile, path] : command_paths_) {
    for (const link::ReceivedCommandFrame& frame : path->feed(samples)) on_command_frame(*profile, frame);
  }
  publish_until(audio_ms());
}

store::ReceptionRow Agent::reception_row(const LinkProfile& profile, double start_ms, double heard_ms, bool intact) const {
  store::ReceptionRow row;
  row.host = options_.host;
  row.profile = profile.name;
  row.started_at = timeline_.wall(start_ms);
  row.heard_at = timeline_.wall(heard_ms);
  row.crc_ok = intact;
  row.reply = intact ? "ack" : "nack";
  return row;
}

void Agent::execute(const command::Command& command, double heard_ms, store::ReceptionRow& row) {
  // Catch up the publish ticks before the command, so it takes effect from its own time.
  publish_until(heard_ms, false);
  provider_.apply(command, heard_ms / 1000.0);
  row.command = command::describe(command);
  row.linear_mps = provider_.velocity().linear_mps;
  row.angular_rps = provider_.velocity().angular_rps;
}

void Agent::told(const HeardFrame& frame) const {
  if (options_.on_frame_heard) options_.on_frame_heard(frame);
}

void Agent::on_word_frame(const LinkProfile& profile, const link::ReceivedFrame& frame) {
  ++frames_heard_;
  replies_.play(reply_audio(profile, frame.crc_ok, std::nullopt), frame.heard_ms);
  store::ReceptionRow row = reception_row(profile, frame.start_ms, frame.heard_ms, frame.crc_ok);
  row.frame = frame.frame;
  row.frame_width = reliability::kFrameBits;
  HeardFrame heard{&profile, frame.start_ms, frame.heard_ms, frame.frame, frame.crc_ok, std::nullopt, std::nullopt};

  const std::string bits = reliability::bit_string(frame.frame);
  if (!frame.crc_ok) {
    spdlog::warn("t={:.3f}s frame {} failed the CRC: NACK", frame.heard_ms / 1000.0, bits);
    store_.write(row);
    told(heard);
    return;
  }
  const command::ReceiverEvent& event = *frame.event;
  row.word = reliability::frame_word(frame.frame);
  heard.word = static_cast<command::Word>(*row.word);
  row.event = command::event_kind_name(event.kind);
  row.command_state = command::state_name(event.state_after);
  std::string what = row.event;
  if (event.kind == command::ReceiverEvent::Kind::ModeSelected) what += " " + command::mode_name(*event.mode);
  if (event.kind == command::ReceiverEvent::Kind::Ignored) what += " (" + event.reason + ")";
  if (event.command) {
    execute(*event.command, frame.heard_ms, row);
    heard.command = event.command;
    what = "command " + row.command;
  }
  spdlog::info("t={:.3f}s frame {} word {}: ACK, {}", frame.heard_ms / 1000.0, bits, *row.word, what);
  store_.write(row);
  told(heard);
}

void Agent::on_command_frame(const LinkProfile& profile, const link::ReceivedCommandFrame& frame) {
  ++frames_heard_;
  const bool intact = frame.frame.has_value();
  replies_.play(reply_audio(profile, intact, intact ? std::optional(frame.frame->sequence) : std::nullopt), frame.heard_ms);
  store::ReceptionRow row = reception_row(profile, frame.start_ms, frame.heard_ms, intact);
  row.frame = static_cast<std::int64_t>(frame.bits);
  row.frame_width = reliability::kCommandFrameBits;
  HeardFrame heard{&profile, frame.start_ms, frame.heard_ms, frame.bits, intact, std::nullopt, std::nullopt};

  const std::string bits = reliability::bit_string(frame.bits, reliability::kCommandFrameBits);
  if (!intact) {
    spdlog::warn("t={:.3f}s {} frame {} failed the CRC{}: NACK", frame.heard_ms / 1000.0, profile.name, bits,
                 frame.error.empty() ? "" : " (" + frame.error + ")");
    row.event = frame.error.empty() ? "" : "refused";
    store_.write(row);
    told(heard);
    return;
  }
  if (frame.repeat) {
    // The sender did not hear our ACK and sent the frame again: answer, do not execute.
    row.event = "repeat";
    spdlog::info("t={:.3f}s {} frame {} seq {}: ACK, a repeat of the last command, not executed again",
                 frame.heard_ms / 1000.0, profile.name, bits, frame.frame->sequence);
  } else {
    row.event = "command";
    execute(*frame.command, frame.heard_ms, row);
    heard.command = frame.command;
    spdlog::info("t={:.3f}s {} frame {} seq {}: ACK, command {}", frame.heard_ms / 1000.0, profile.name, bits,
                 frame.frame->sequence, row.command);
  }
  store_.write(row);
  told(heard);
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
  const std::vector<float> silence(static_cast<std::size_t>(block_samples_), 0.0f);
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
