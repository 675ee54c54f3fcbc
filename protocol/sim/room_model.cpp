#include "sim/room_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

#include "sim/measured_rir.h"
#include "sim/number_text.h"
#include "sim/room_calibration.h"
#include "sim/room_decay.h"

namespace dtmf::sim {

namespace {

std::string fixed(double v, int decimals = 2) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

std::string point_text(const Point3& p) { return "(" + fixed(p.x) + ", " + fixed(p.y) + ", " + fixed(p.z) + ") m"; }

std::string bands_text(const BandValues& v) {
  if (std::all_of(v.begin(), v.end(), [&](double x) { return x == v[0]; })) return fixed(v[0], 3);
  std::string text;
  for (std::size_t b = 0; b < v.size(); ++b)
    text += (b ? "," : "") + fixed(kOctaveCentresHz[b], 0) + ":" + fixed(v[b], 3);
  return text;
}

}  // namespace

RoomModel::RoomModel(const RoomConfig& config, int sample_rate_hz) : config_(config), sample_rate_hz_(sample_rate_hz) {
  if (!config.enabled()) throw std::invalid_argument("no room given: a measured response file or a shoebox room");
  if (!config.rir_file.empty() && config.shoebox) {
    throw std::invalid_argument(
        "a room is either measured (a response file) or simulated (a shoebox), not both: choose one");
  }
  if (!config.rir_file.empty()) {
    kind_ = Kind::Measured;
    MeasuredRir rir = load_measured_rir(config.rir_file, sample_rate_hz);
    direct_index_ = rir.direct_index;
    rt60_s_ = rt60_t20_s(rir.samples, sample_rate_hz);
    measured_note_ = "measured room '" + config.rir_file + "' (channel 0 of " + std::to_string(rir.file_channels) +
                     ", " + std::to_string(rir.file_rate_hz) + " Hz), " +
                     fixed(static_cast<double>(rir.samples.size()) / sample_rate_hz) + " s";
    measured_ = std::make_shared<const std::vector<float>>(std::move(rir.samples));
    return;
  }
  kind_ = Kind::ImageSource;
  check_room(*config.shoebox);
  const Point3 size = config.shoebox->size_m;
  mic_ =
      config.mic_at.value_or(Point3{std::min(1.0, size.x / 4), 0.4 * size.y, std::min(kDefaultMicHeightM, size.z / 2)});
  check_inside(*config.shoebox, mic_, "the microphone");
  if (config.target_rt60_s == 0)
    room_ = config.shoebox;
  else if (!(config.target_rt60_s > 0))
    throw std::invalid_argument("RT60 " + number_text(config.target_rt60_s) + " s: give a time above 0");
}

Point3 RoomModel::speaker_at_distance(double distance_m) const {
  if (kind_ != Kind::ImageSource) throw std::logic_error("speaker_at_distance() is for image-source rooms");
  if (!std::isfinite(distance_m) || distance_m < 0.01) {
    throw std::invalid_argument("loudspeaker distance " + number_text(distance_m) + " m: give at least 0.01 m");
  }
  const ShoeboxRoom& box = *config_.shoebox;
  const auto place = [&](double d) {
    const double rise = std::min({kMaxSpeakerRiseM, 0.5 * d, box.size_m.z - 0.01 - mic_.z});
    const double across = std::sqrt(std::max(0.0, d * d - rise * rise));
    // Towards the farthest corner of the floor plan, where the most distance fits.
    const double cx = mic_.x < box.size_m.x / 2 ? box.size_m.x : 0, cy = mic_.y < box.size_m.y / 2 ? box.size_m.y : 0;
    const double dx = cx - mic_.x, dy = cy - mic_.y, norm = std::hypot(dx, dy);
    return Point3{mic_.x + across * dx / norm, mic_.y + across * dy / norm, mic_.z + rise};
  };
  const auto fits = [&](double d) {
    try {
      check_inside(box, place(d), "");
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  if (!fits(distance_m)) {
    double lo = 0.01, hi = distance_m;  // the farthest that fits, for the message
    for (int i = 0; i < 40; ++i) (fits((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
    throw std::invalid_argument("a loudspeaker " + number_text(distance_m) +
                                " m from the microphone does not fit in the " + number_text(box.size_m.x) + " x " +
                                number_text(box.size_m.y) + " x " + number_text(box.size_m.z) +
                                " m room (towards its farthest corner at most " + fixed(lo) +
                                " m fit): give a shorter distance, a larger room, or the loudspeaker's position");
  }
  return place(distance_m);
}

ShoeboxRoom RoomModel::shoebox() const {
  if (kind_ != Kind::ImageSource) throw std::logic_error("shoebox() is for image-source rooms");
  std::lock_guard lock(mutex_);
  return room_.value_or(*config_.shoebox);
}

Response RoomModel::between(const Point3& speaker, const Point3& mic) const {
  if (kind_ != Kind::ImageSource) throw std::logic_error("between() is for image-source rooms");
  std::lock_guard lock(mutex_);
  if (!room_) {
    const CalibratedRoom c =
        calibrate_rt60(*config_.shoebox, speaker, mic, config_.target_rt60_s, sample_rate_hz_, config_.seed);
    room_ = c.room;
    calibration_note_ =
        " (tuned to RT60 " + fixed(config_.target_rt60_s) + " s in " + std::to_string(c.tries) + " tries)";
  }
  // The pair in a fixed order: A to B and B to A are one response (reciprocity).
  std::array<double, 6> key = {speaker.x, speaker.y, speaker.z, mic.x, mic.y, mic.z};
  if (std::make_tuple(mic.x, mic.y, mic.z) < std::make_tuple(speaker.x, speaker.y, speaker.z)) {
    key = {mic.x, mic.y, mic.z, speaker.x, speaker.y, speaker.z};
  }
  if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
  auto h = std::make_shared<const std::vector<float>>(
      image_source_response(*room_, speaker, mic, sample_rate_hz_, config_.seed));
  if (!rt60_s_) rt60_s_ = rt60_t20_s(*h, sample_rate_hz_);
  cache_.emplace(key, h);
  return h;
}

Response RoomModel::measured_at(double distance_m) const {
  if (kind_ != Kind::Measured) throw std::logic_error("measured_at() is for measured rooms");
  if (distance_m == 1) return measured_;
  std::lock_guard lock(mutex_);
  if (const auto it = distance_cache_.find(distance_m); it != distance_cache_.end()) return it->second;
  // The channel scales the whole path by 1/d: the reverberation, scaled by d here first,
  // keeps its level at 1 m, near the source or far from it.
  auto at = std::make_shared<std::vector<float>>(*measured_);
  const auto reverberation_from = direct_index_ + static_cast<std::size_t>(kRirDirectAfterS * sample_rate_hz_);
  for (std::size_t i = reverberation_from; i < at->size(); ++i) (*at)[i] *= static_cast<float>(distance_m);
  Response h = std::move(at);
  distance_cache_.emplace(distance_m, h);
  return h;
}

std::optional<double> RoomModel::rt60_s() const {
  std::lock_guard lock(mutex_);
  return rt60_s_;
}

std::string RoomModel::describe() const {
  std::lock_guard lock(mutex_);
  const std::string rt60 = rt60_s_ ? ", RT60 (T20) " + fixed(*rt60_s_) + " s" : "";
  if (kind_ == Kind::Measured) return measured_note_ + rt60;
  const ShoeboxRoom& r = room_ ? *room_ : *config_.shoebox;
  const bool same_walls = r.reflection[kWallX0] == r.reflection[kWallX1] &&
                          r.reflection[kWallX0] == r.reflection[kWallY0] &&
                          r.reflection[kWallX0] == r.reflection[kWallY1];
  const std::string walls =
      same_walls ? "walls " + bands_text(r.reflection[kWallX0])
                 : "walls x0 " + bands_text(r.reflection[kWallX0]) + ", x1 " + bands_text(r.reflection[kWallX1]) +
                       ", y0 " + bands_text(r.reflection[kWallY0]) + ", y1 " + bands_text(r.reflection[kWallY1]);
  return "image-source room " + number_text(r.size_m.x) + " x " + number_text(r.size_m.y) + " x " +
         number_text(r.size_m.z) + " m, reflection: " + walls + ", floor " + bands_text(r.reflection[kFloor]) +
         ", ceiling " + bands_text(r.reflection[kCeiling]) + calibration_note_ + ", microphone at " + point_text(mic_) +
         rt60;
}

}  // namespace dtmf::sim
