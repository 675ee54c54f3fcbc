// Physical layer, rooms: the room a channel's sound travels through, prepared once.
//
// Either a measured room (a RIR file, measured_rir.h) or an image-source shoebox
// (image_source_room.h), possibly tuned to an RT60 (room_calibration.h). A RoomModel is
// prepared once — reading and resampling a file, or calibrating a shoebox, takes up to a
// second or two — and then hands out the impulse response of each path, which the channel
// convolves with what the loudspeaker plays. One model may serve several channels (the
// two directions of SimulatedAir, a benchmark's many trials); it is thread-safe.
//
// Distance and level (docs/protocol.md §7):
//   - A measured room's response already holds its own propagation: the delay, spreading
//     and absorption between the loudspeaker and the microphone where it was measured. Every
//     transmitter hears that one response and its distance adds no delay or absorption. Only
//     the direct sound follows the distance, by 1/d relative to 1 m (it carries a unit
//     impulse's energy); the rest of the response keeps its level at 1 m (measured_at). A
//     room's reverberant field does not depend on where the source stands: its level is the
//     source's power over the room's absorption (Sabine; Hopkins and Stryker's
//     L = Lw + 10 lg(Q / 4 pi r^2 + 4 / R)). Scaling the whole response by 1/d made the own
//     reverberation of a loudspeaker 0.1 m away 20 dB louder than any room makes it, and a
//     frame from 3 m 9.5 dB less reverberant than the room makes it, against the robot's own
//     answer ringing in the same room at its true level (docs/protocol.md §7).
//   - In an image-source room, positions decide everything: the response holds the delay,
//     1/d and air absorption of every path. A transmitter given by its distance stands at
//     that distance from the microphone, towards the room's farthest corner from it, and
//     higher than the microphone by half the distance, at most 0.75 m (a loudspeaker on a
//     desk when the robot's microphone is near the floor).
//   - The microphone stands at mic_at, by default 5 cm above the floor (a TurtleBot3's),
//     1 m from the x = 0 wall (or a quarter of the room) and at 40 % of the room's width
//     (off the middle: a position on a symmetry plane doubles some reflections exactly).
//   - Calibration to an RT60 is done on the first path asked for.
// Reciprocity: the response from a loudspeaker at A to a microphone at B is the response
// from B to A (exactly so for the image-source room; a measured room has one response).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sim/image_source_room.h"

namespace dtmf::sim {

inline constexpr double kDefaultMicHeightM = 0.05;
inline constexpr double kMaxSpeakerRiseM = 0.75;

struct RoomConfig {
  std::string rir_file;                // a measured room, or
  std::optional<ShoeboxRoom> shoebox;  // an image-source room
  double target_rt60_s = 0;            // shoebox: > 0 tunes the walls and ceiling to this RT60 (T20)
  std::optional<Point3> mic_at;        // shoebox: the microphone (default above); loudspeakers are
                                       // placed by the channel (AcousticChannel::add_transmitter_at)
  std::uint64_t seed = 1;              // shoebox: the image randomization; not the noise seed, so that
                                       // both directions of a link hear the same room

  bool enabled() const { return !rir_file.empty() || shoebox.has_value(); }
};

using Response = std::shared_ptr<const std::vector<float>>;

class RoomModel {
 public:
  enum class Kind { Measured, ImageSource };

  // Loads the file or checks the shoebox; std::invalid_argument / AudioError with a clear
  // message for anything wrong (both a file and a shoebox, a position outside the room...).
  RoomModel(const RoomConfig& config, int sample_rate_hz);

  Kind kind() const { return kind_; }
  int sample_rate_hz() const { return sample_rate_hz_; }

  // Measured: the one response (its direct sound of unit energy, peaking at direct_index()).
  Response measured() const { return measured_; }
  // Measured: the response of a loudspeaker `distance_m` away before the path's 1/d: its
  // reverberation (after the direct sound) scaled by d, so that after 1/d only the direct
  // sound has grown or fallen. Cached per distance.
  Response measured_at(double distance_m) const;
  std::size_t direct_index() const { return direct_index_; }

  // Image source: the response from a loudspeaker at `speaker` to a microphone at `mic`.
  Response between(const Point3& speaker, const Point3& mic) const;
  Point3 microphone() const { return mic_; }
  // Where a loudspeaker `distance_m` from the microphone stands (see above).
  Point3 speaker_at_distance(double distance_m) const;
  ShoeboxRoom shoebox() const;

  // T20 of the measured response, or of the first image-source path made.
  std::optional<double> rt60_s() const;
  // One line: what the room is and what it measured.
  std::string describe() const;

 private:
  const RoomConfig config_;
  const int sample_rate_hz_;
  Kind kind_;
  Response measured_;
  std::size_t direct_index_ = 0;
  std::string measured_note_;
  Point3 mic_;
  mutable std::mutex mutex_;
  mutable std::optional<ShoeboxRoom> room_;  // after calibration
  mutable std::string calibration_note_;
  mutable std::optional<double> rt60_s_;
  mutable std::map<std::array<double, 6>, Response> cache_;
  mutable std::map<double, Response> distance_cache_;
};

}  // namespace dtmf::sim
