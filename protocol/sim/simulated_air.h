// Physical layer: a simulated room that runs in real time, for whole systems.
//
// Stations — a loudspeaker and a microphone each, like the sender's computer and the robot
// — stand at positions on a line. Every `block_ms` of real time a clock thread takes the
// next block from every loudspeaker (silence if it has nothing), passes it through one
// AcousticChannel per microphone (each loudspeaker at its distance, its own at 0.1 m) and
// appends the result to that microphone. Loudspeakers and microphones behave like devices:
// write() returns once the samples are queued close to playing, drain() once they played,
// read() blocks until the samples have been "recorded". So a server and an agent in one
// process talk through it exactly as through a real room, only without a sound card.
//
// A room in the configuration (room_model.h) is prepared once and serves every path, both
// ways. Reciprocity: the response from station A's loudspeaker to B's microphone is the one
// from B's loudspeaker to A's microphone (a station's loudspeaker and microphone stand at
// one point for the paths between stations), so the robot's ACK crosses the same room as
// the command did. In a measured room every path hears the one response at 1/d — a
// station's own loudspeaker, 0.1 m away, too: its reverberation then comes 20 dB louder
// as well, since one measured response cannot tell its direct part from the room's. In a
// shoebox, station p stands at the room's microphone position moved p metres along x (its
// own loudspeaker 0.1 m beside its microphone). Radial motion (config.motion) moves the
// paths between stations, not a station's own.
#pragma once

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "physical/audio_io.h"
#include "sim/acoustic_channel.h"

namespace dtmf::sim {

class SimulatedAir {
 public:
  struct Station {
    std::unique_ptr<physical::AudioSink> speaker;
    std::unique_ptr<physical::AudioSource> microphone;
  };

  SimulatedAir(int sample_rate_hz, ChannelConfig config, double block_ms = 10);
  ~SimulatedAir();
  SimulatedAir(const SimulatedAir&) = delete;
  SimulatedAir& operator=(const SimulatedAir&) = delete;

  // Before start(). The endpoints stay valid while the air lives.
  Station add_station(const std::string& name, double position_m);
  void start();
  // Microphones then report the end of the stream; loudspeakers refuse to play.
  void stop();
  // A station's loudspeaker goes silent (muted) or sounds again: what it is given still
  // plays on time, unheard, as when something stands before the loudspeaker. Benchmarks cut
  // the link so at a chosen moment, in the middle of a frame or between two.
  void mute(const std::string& station, bool muted);

  struct Shared;  // state shared with the endpoints

 private:
  void run();

  std::shared_ptr<Shared> shared_;
  std::thread clock_;
};

}  // namespace dtmf::sim
