// The robot agent's core: the receive paths wired to its answers, its logs and the wheels.
//
//   audio block -> every listened-with link's FrameReceiver (link/link.h)
//      each verdict -> its link's answer: ACK if intact (naming the frame where the format
//                      does), NACK if not (ReplyPlayer)
//                       -> a receptions row (store)
//                       -> a complete, new command -> VelocityProvider
//   every publish period, and the end of each ramp (a Velocity reached, a lease's
//   standstill) -> VelocityProvider::update -> every cmd_vel output
//
// The agent listens with every profile it is given at once, so the sender may choose the
// profile per command.
//
// The agent's clock is the audio itself: milliseconds of samples heard since start. A live
// device delivers them in real time; a file as fast as it can be read, so an offline run
// behaves exactly as a live one would, only faster. Wall times (DDS stamps, database rows)
// come from a Timeline that maps audio time to the wall clock.
#pragma once

#include <chrono>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "cmd_vel/velocity.h"
#include "link/link.h"
#include "profile/link_profile.h"
#include "refusal_burst.h"
#include "reply_player.h"
#include "store.h"
#include "velocity_provider.h"

namespace dtmf::agent {

// Audio time -> wall time. Live: anchored at the last block read (the block just captured
// ends now). Offline: the start of the run plus the audio time.
class Timeline {
 public:
  explicit Timeline(bool live) : live_(live), start_(std::chrono::system_clock::now()) {}
  // A recording's audio time 0 is now: called as its first block is read, so that the
  // stamps of a recording heard in real time (--realtime) are publish times.
  void start_now() { start_ = std::chrono::system_clock::now(); }
  // The block ending at `block_end_ms` of audio was read `queued_ms` of audio behind the
  // microphone: its end was captured that long before now.
  void block_read(double block_end_ms, double queued_ms = 0) {
    block_end_ms_ = block_end_ms;
    if (live_) {
      block_end_wall_ =
          std::chrono::system_clock::now() - std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                                 std::chrono::duration<double, std::milli>(queued_ms));
    }
  }
  std::chrono::system_clock::time_point wall(double audio_ms) const {
    const auto offset = [](double ms) {
      return std::chrono::duration_cast<std::chrono::system_clock::duration>(
          std::chrono::duration<double, std::milli>(ms));
    };
    return live_ ? block_end_wall_ - offset(block_end_ms_ - audio_ms) : start_ + offset(audio_ms);
  }

 private:
  bool live_;
  std::chrono::system_clock::time_point start_;
  std::chrono::system_clock::time_point block_end_wall_;
  double block_end_ms_ = 0;
};

// A frame the agent heard and answered, whatever its profile: its link's reception of it
// (link/reception.h), under which profile, and the command it executed (none for a frame
// refused, broken, or repeated after a lost ACK).
struct HeardFrame {
  const LinkProfile* profile = nullptr;
  link::Reception reception;
  std::optional<command::Command> executed;
};

struct AgentOptions {
  // The profiles to listen with; all must share one sample rate.
  std::vector<const LinkProfile*> profiles{&seed_profile()};
  // The key, the counters and this robot's address (dtmf-agent --key, --state-dir, --address).
  link::LinkOptions link;
  command::RobotModel model = command::burger();
  double publish_rate_hz = 20;
  double continuous_limit_s = 30;
  std::string host;  // for the receptions rows
  // Told of every frame heard, after it was handled (for monitors and tests).
  std::function<void(const HeardFrame&)> on_frame_heard;
};

class Agent {
 public:
  Agent(AgentOptions options, ReplyPlayer& replies, std::vector<CmdVelOutput*> outputs, store::Store& store,
        Timeline& timeline);

  // One block of audio, as captured.
  // `queued_ms`: audio captured after these samples and not yet read (see Timeline).
  void process(std::span<const float> samples, double queued_ms = 0);
  // The input has ended: let a timed motion run out (as silence), then stop the wheels.
  // `after_block` runs after each block of that silence (to pace it in real time).
  void finish(const std::function<void()>& after_block = {});
  // Stop the wheels now and say so on every output (shutdown).
  void stop_now(const std::string& why);

  double audio_ms() const;
  // The block size that suits every profile listened with (its smallest analysis hop).
  int block_samples() const { return block_samples_; }
  const VelocityProvider& provider() const { return provider_; }
  std::size_t frames_heard() const { return frames_heard_; }
  // Echoes of frames taken lately that the receivers ignored (reliability/echo_memory.h).
  std::size_t echoes_ignored() const;

 private:
  void on_reception(const link::Link& link, const link::Reception& reception);
  // The command takes effect from `heard_ms`; the row gets the velocity it set.
  void execute(const command::Command& command, double start_ms, double heard_ms, store::ReceptionRow& row);
  void told(const HeardFrame& frame) const;
  // Publishes every tick up to audio_ms (including a tick at exactly audio_ms if inclusive),
  // and the moments between ticks when a ramp ends (VelocityProvider::settles_at_s).
  void publish_until(double audio_ms, bool inclusive = true);
  void publish(const Velocity& velocity, double audio_ms);

  AgentOptions options_;
  ReplyPlayer& replies_;
  std::vector<CmdVelOutput*> outputs_;
  store::Store& store_;
  Timeline& timeline_;
  int sample_rate_hz_;
  int block_samples_;
  // One link and its receive path per profile listened with.
  std::vector<std::unique_ptr<link::Link>> links_;
  std::vector<std::pair<const link::Link*, std::unique_ptr<link::FrameReceiver>>> receivers_;
  VelocityProvider provider_;
  long long samples_ = 0;
  double next_publish_ms_ = 0;
  double published_ms_ = -1;  // the last sample's audio time
  std::size_t frames_heard_ = 0;
  RefusalBurst forgeries_;  // refusals for authentication: a burst is said once
  // The last intact frame's link, and until when (audio ms) that frame and its answer sound.
  const link::Link* sounding_link_ = nullptr;
  double sounding_until_ms_ = 0;
};

}  // namespace dtmf::agent
