#include "watch_air_rpc.h"

#include <spdlog/spdlog.h>

#include "command/overloaded.h"
#include "request_validation.h"
#include "teleop_service.h"

namespace dtmf::server {

namespace {

void fill_event(v1::WatchAirResponse& out, const AirEvent& event) {
  std::visit(command::Overloaded{
                 [&](const FramePlayed& e) {
                   v1::FramePlayed& f = *out.mutable_frame_played();
                   f.set_command_id(e.command_id);
                   f.set_command(e.command);
                   for (const auto& r : e.robots) f.add_robots(r);
                   f.set_kind(e.kind);
                   f.set_profile(e.profile);
                   if (e.sequence) f.set_sequence(*e.sequence);
                   if (e.counter) f.set_counter(*e.counter);
                   f.set_authenticated(e.authenticated);
                   f.set_frame_index(static_cast<std::uint32_t>(e.frame_index));
                   f.set_frame_count(static_cast<std::uint32_t>(e.frame_count));
                   f.set_attempt(static_cast<std::uint32_t>(e.attempt));
                   f.set_chord_ms(e.chord_ms);
                   f.set_air_wait_ms(e.air_wait_ms);
                 },
                 [&](const FrameAnswered& e) {
                   v1::FrameAnswered& f = *out.mutable_frame_answered();
                   f.set_command_id(e.command_id);
                   f.set_robot(e.robot);
                   f.set_frame_index(static_cast<std::uint32_t>(e.frame_index));
                   f.set_attempt(static_cast<std::uint32_t>(e.attempt));
                   f.set_answer(e.answer);
                   f.set_authenticated(e.authenticated);
                   if (e.response_time_ms) f.set_response_time_ms(*e.response_time_ms);
                 },
                 [&](const AnswerHeard& e) {
                   v1::AnswerHeard& a = *out.mutable_answer_heard();
                   a.set_robot(e.robot);
                   a.set_profile(e.profile);
                   a.set_ack(e.ack);
                   if (e.sequence) a.set_sequence(*e.sequence);
                   a.set_tagged(e.tagged);
                   if (e.address) a.set_address(*e.address);
                   a.set_level_dbfs(e.level_dbfs);
                 },
                 [&](const AirWaiting& e) {
                   v1::AirWaiting& w = *out.mutable_air_waiting();
                   w.set_command_id(e.command_id);
                   w.set_robot(e.robot);
                   w.set_reason(e.reason);
                   w.set_left_ms(e.left_ms);
                 },
                 [&](const AirBusy& e) {
                   v1::AirBusy& b = *out.mutable_air_busy();
                   b.set_busy(e.busy);
                   b.set_level_dbfs(e.level_dbfs);
                   b.set_floor_dbfs(e.floor_dbfs);
                 },
                 [&](const CommandEnded& e) {
                   v1::CommandEnded& c = *out.mutable_command_ended();
                   c.set_command_id(e.command_id);
                   c.set_robot(e.robot);
                   c.set_command(e.command);
                   c.set_outcome(e.outcome);
                   c.set_detail(e.detail);
                 },
                 [&](const SpectrumColumn& e) {
                   v1::SpectrumColumn& c = *out.mutable_spectrum();
                   c.set_low_hz(e.low_hz);
                   c.set_step_hz(e.step_hz);
                   c.set_window_ms(e.window_ms);
                   c.mutable_level_dbfs()->Assign(e.level_dbfs.begin(), e.level_dbfs.end());
                 },
             },
             event.what);
}

// The reactor's lock and its pointer, shared with the fan-out's ready callback: the callback
// may run after the reactor is gone (copied before it unwatched), and then finds none.
struct WatchState {
  std::recursive_mutex mutex;  // a write's completion may come back on the thread that started it
  class WatchAirReactor* reactor = nullptr;
};

class WatchAirReactor final : public grpc::ServerWriteReactor<v1::WatchAirResponse> {
 public:
  WatchAirReactor(AirFanout& fanout, std::shared_ptr<AirWatch> watch)
      : fanout_(fanout), watch_(std::move(watch)), state_(std::make_shared<WatchState>()) {
    std::lock_guard lock(state_->mutex);
    state_->reactor = this;
    fanout_.on_ready(watch_, [state = state_] {
      std::lock_guard ready_lock(state->mutex);
      if (state->reactor) state->reactor->pump();
    });
    pump();
  }

  void OnWriteDone(bool ok) override {
    std::lock_guard lock(state_->mutex);
    writing_ = false;
    if (!ok) return finish({grpc::StatusCode::CANCELLED, "the watcher went away"});
    pump();
  }
  void OnCancel() override {
    std::lock_guard lock(state_->mutex);
    finish(grpc::Status::CANCELLED);
  }
  void OnDone() override {
    {
      std::lock_guard lock(state_->mutex);
      state_->reactor = nullptr;
    }
    fanout_.unwatch(watch_);
    delete this;
  }

  // Under the state's lock: the next entry on its way, or the stream's end once the fan-out closed.
  void pump() {
    if (writing_ || finished_) return;
    if (std::optional<WatchEntry> entry = fanout_.take(*watch_)) {
      message_.Clear();
      fill_watch_response(message_, *entry);
      writing_ = true;
      StartWrite(&message_);
    } else if (fanout_.closed()) {
      finish({grpc::StatusCode::UNAVAILABLE, "the server is stopping: nothing more goes on the air"});
    }
  }

 private:
  void finish(const grpc::Status& status) {
    if (finished_) return;
    finished_ = true;
    fanout_.unwatch(watch_);  // before the status goes: a client told it ended may watch again at once
    Finish(status);
  }

  AirFanout& fanout_;
  std::shared_ptr<AirWatch> watch_;
  std::shared_ptr<WatchState> state_;
  v1::WatchAirResponse message_;
  bool writing_ = false;  // guarded by the state's lock, as is what follows
  bool finished_ = false;
};

}  // namespace

void fill_watch_response(v1::WatchAirResponse& out, const WatchEntry& entry) {
  out.set_audio_ms(entry.event.audio_ms);
  out.set_time_unix_ms(
      std::chrono::duration_cast<std::chrono::milliseconds>(entry.event.wall.time_since_epoch()).count());
  out.set_dropped_events(entry.dropped_events);
  out.set_dropped_columns(entry.dropped_columns);
  fill_event(out, entry.event);
}

WatchOptions watch_options(const v1::WatchAirRequest& request) {
  WatchOptions o;
  check_robot_name("robot", request.robot());
  o.robot = request.robot();
  o.spectrum = request.spectrum();
  if (request.columns_per_s() != 0) o.columns_per_s = request.columns_per_s();
  if (request.bins() > static_cast<unsigned>(kMaxColumnBins))
    throw std::invalid_argument("bins " + std::to_string(request.bins()) + " is over the cap: give 0 (" +
                                std::to_string(kDefaultColumnBins) + " bins) up to " + std::to_string(kMaxColumnBins));
  if (request.bins() != 0) o.bins = static_cast<int>(request.bins());
  return o;
}

namespace {
// A watch refused before it began: its status, and done.
class RefusedWatch final : public grpc::ServerWriteReactor<v1::WatchAirResponse> {
 public:
  explicit RefusedWatch(const grpc::Status& status) { Finish(status); }
  void OnDone() override { delete this; }
};
}  // namespace

grpc::ServerWriteReactor<v1::WatchAirResponse>* TeleopService::WatchAir(grpc::CallbackServerContext*,
                                                                        const v1::WatchAirRequest* request) {
  std::shared_ptr<AirWatch> watch;
  try {
    WatchOptions options = watch_options(*request);
    if (!options.robot.empty()) transmitter_.robot_named(options.robot);
    watch = transmitter_.air_events().watch(std::move(options));
  } catch (const std::invalid_argument& e) {
    return new RefusedWatch({grpc::StatusCode::INVALID_ARGUMENT, e.what()});
  }
  if (!watch) {
    return new RefusedWatch({grpc::StatusCode::RESOURCE_EXHAUSTED,
                             "already " + std::to_string(kMaxWatchers) +
                                 " watchers watch the air (or the server is stopping): end one, or try later"});
  }
  return new WatchAirReactor(transmitter_.air_events(), std::move(watch));
}

}  // namespace dtmf::server
