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
  links_ = link::make_links(options_.link, options_.profiles);
  block_samples_ = links_.front()->receiver_block_samples();
  for (const auto& l : links_) {
    if (l->profile().sample_rate_hz != sample_rate_hz_) {
      throw std::invalid_argument("profiles " + options_.profiles.front()->name + " and " + l->name() +
                                  " use different sample rates and cannot share a microphone");
    }
    block_samples_ = std::min(block_samples_, l->receiver_block_samples());
    receivers_.emplace_back(l.get(), l->receiver());
  }
}

double Agent::audio_ms() const { return static_cast<double>(samples_) * 1000.0 / sample_rate_hz_; }

void Agent::process(std::span<const float> samples, double queued_ms) {
  samples_ += static_cast<long long>(samples.size());
  timeline_.block_read(audio_ms(), queued_ms);
  // Frames first: a command heard in this block takes effect from its own time, so the
  // publish ticks of this block already carry it.
  for (auto& [link, receiver] : receivers_) {
    for (const link::Reception& reception : receiver->feed(samples)) on_reception(*link, reception);
  }
  publish_until(audio_ms());
}

void Agent::execute(const command::Command& command, double start_ms, double heard_ms, store::ReceptionRow& row) {
  // Catch up the publish ticks before the command, so it takes effect from its own time.
  publish_until(heard_ms, false);
  provider_.apply(command, heard_ms / 1000.0, start_ms / 1000.0);
  row.command = command::describe(command);
  row.linear_mps = provider_.target().linear_mps;
  row.angular_radps = provider_.target().angular_radps;
}

std::size_t Agent::echoes_ignored() const {
  std::size_t echoes = 0;
  for (const auto& [link, receiver] : receivers_) echoes += receiver->echoes_ignored();
  return echoes;
}

void Agent::told(const HeardFrame& frame) const {
  if (options_.on_frame_heard) options_.on_frame_heard(frame);
}

void Agent::on_reception(const link::Link& link, const link::Reception& r) {
  const LinkProfile& profile = link.profile();
  // A frame that fails while another profile's intact frame, or the answer to it, still
  // sounds is that sound's doing, not a damaged frame of this profile: a sender plays one
  // frame at a time, so none of this profile was on the air then. (Where the microphone
  // clips under the robot's own seed ACK, ACK and seed chord make tones in every fast band
  // at once; the fast receiver now and then took them for a damaged frame and NACKed it.)
  if (!r.intact && sounding_link_ && sounding_link_ != &link && r.start_ms < sounding_until_ms_) {
    spdlog::debug("t={:.3f}s {} candidate during a {} frame: not answered", r.heard_ms / 1000.0, profile.name,
                  sounding_link_->name());
    return;
  }
  ++frames_heard_;
  std::vector<float> answer = link.answer_audio(r);
  if (r.intact) {
    sounding_link_ = &link;
    const double frame_period_ms = link.frame_start_ms(1) - link.frame_start_ms(0);
    sounding_until_ms_ = std::max(r.start_ms + frame_period_ms,
                                  r.heard_ms + 1000.0 * static_cast<double>(answer.size()) / sample_rate_hz_);
  }
  if (r.answered) replies_.play(std::move(answer), r.heard_ms);
  store::ReceptionRow row;
  row.host = options_.host;
  row.robot_address = link.options().address;
  row.profile = profile.name;
  row.started_at = timeline_.wall(r.start_ms);
  row.heard_at = timeline_.wall(r.heard_ms);
  row.crc_ok = r.intact;
  if (r.answered) row.reply = r.acknowledged() ? "ack" : "nack";
  row.frame = r.bits.decimal();
  row.frame_width = r.bit_count;
  row.event = link::event_name(r.event);
  row.reason = link::reason_name(r.refusal);
  row.authenticated = r.authenticated;
  if (r.payload_word) row.word = *r.payload_word;
  if (!r.command_state.empty()) row.command_state = r.command_state;
  HeardFrame heard{&profile, r, std::nullopt};

  const std::string bits = r.bits.bit_string(r.bit_count);
  const std::string number = r.counter    ? " counter " + std::to_string(*r.counter)
                             : r.sequence ? " seq " + std::to_string(*r.sequence)
                                          : "";
  const char* refusal_answer = r.answered ? "NACK" : "not answered (it may be another robot's)";
  if (!r.intact) {
    spdlog::warn("t={:.3f}s {} frame {} failed the check{}: {}", r.heard_ms / 1000.0, profile.name, bits,
                 r.detail.empty() ? "" : " (" + r.detail + ")", refusal_answer);
    store_.write(row);
    told(heard);
    return;
  }
  if (r.event == link::ReceptionEvent::Refused) {
    spdlog::warn("t={:.3f}s {} frame {}{} refused ({}): {}: {}", r.heard_ms / 1000.0, profile.name, bits, number,
                 link::reason_name(r.refusal), r.detail, refusal_answer);
    if (r.refusal == link::RefusalReason::Authentication) {
      if (const auto burst = forgeries_.refused(r.heard_ms)) {
        spdlog::warn(
            "t={:.3f}s {} frames refused for authentication in the last minute (a burst: {} a minute or more): "
            "someone may be playing forged or recorded frames, or a sender uses another key (compare the key ids "
            "both sides log at start); each is in the receptions table, and the run report shows the peak",
            r.heard_ms / 1000.0, *burst, kBurstPerMinute);
      }
    }
    store_.write(row);
    told(heard);
    return;
  }
  if (r.command) {
    execute(*r.command, r.start_ms, r.heard_ms, row);
    heard.executed = r.command;
  }
  // A stop for every robot is no robot's to answer (link/frame_admission.h).
  spdlog::info("t={:.3f}s {} frame {}{}{}{}: {} ({}), {}", r.heard_ms / 1000.0, profile.name, bits, number,
               r.payload_word ? " word " + std::to_string(*r.payload_word) : "",
               r.authenticated ? " authenticated" : "", r.answered ? "ACK" : "not answered", link::event_name(r.event),
               r.detail);
  store_.write(row);
  told(heard);
}

void Agent::publish(const Velocity& velocity, double audio_ms) {
  published_ms_ = audio_ms;
  const auto stamp = timeline_.wall(audio_ms);
  for (CmdVelOutput* output : outputs_) output->publish(velocity, audio_ms, stamp);
}

void Agent::publish_until(double audio_ms, bool inclusive) {
  const double period_ms = 1000.0 / options_.publish_rate_hz;
  for (;;) {
    // Besides every period, the moment the wheels reach a new velocity or stand still at a
    // lease's end: cmd_vel carries a key press, and the lease's stop, without waiting for
    // the next period.
    double at_ms = next_publish_ms_;
    if (const auto settles_s = provider_.settles_at_s()) {
      if (const double settles_ms = *settles_s * 1000; settles_ms > published_ms_ && settles_ms < at_ms) {
        at_ms = settles_ms;
      }
    }
    if (!(at_ms < audio_ms || (inclusive && at_ms == audio_ms))) return;
    const Velocity velocity = provider_.update(at_ms / 1000.0);
    if (auto reason = provider_.take_stop_reason()) spdlog::info("t={:.3f}s stop: {}", at_ms / 1000.0, *reason);
    publish(velocity, at_ms);
    if (at_ms == next_publish_ms_) next_publish_ms_ += period_ms;
  }
}

void Agent::finish(const std::function<void()>& after_block) {
  // A timed or leased motion still running at the end of the recording runs out as if in
  // silence.
  const std::vector<float> silence(static_cast<std::size_t>(block_samples_), 0.0f);
  while (provider_.changing_by_itself()) {
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
