#include "sim/simulated_air.h"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>

namespace dtmf::sim {

namespace {
constexpr double kOwnSpeakerDistanceM = 0.1;
constexpr double kMaxRecordingBacklogS = 10;  // a microphone nobody reads drops its oldest audio
}  // namespace

struct SimulatedAir::Shared {
  std::shared_ptr<const RoomModel> room;  // one room for every path, both ways
  struct StationState {
    std::string name;
    double position_m;
    std::deque<float> to_play;
    std::deque<float> recorded;
    bool muted = false;
    std::unique_ptr<AcousticChannel> channel;  // what this station's microphone hears
  };
  int sample_rate_hz;
  ChannelConfig config;
  std::size_t block;
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<StationState> stations;
  bool running = false;
  bool stopped = false;
};

namespace {

class AirSpeaker : public physical::AudioSink {
 public:
  AirSpeaker(std::shared_ptr<SimulatedAir::Shared> shared, std::size_t index)
      : shared_(std::move(shared)), index_(index) {}
  void write(std::span<const float> samples) override {
    std::unique_lock lock(shared_->mutex);
    check();
    auto& queue = shared_->stations[index_].to_play;
    queue.insert(queue.end(), samples.begin(), samples.end());
    // Like a device: return once what is queued is about to play.
    shared_->changed.wait(lock, [&] { return shared_->stopped || queue.size() <= 2 * shared_->block; });
    check();
  }
  void drain() override {
    std::unique_lock lock(shared_->mutex);
    shared_->changed.wait(lock, [&] { return shared_->stopped || shared_->stations[index_].to_play.empty(); });
  }
  int sample_rate_hz() const override { return shared_->sample_rate_hz; }
  std::string describe() const override { return "simulated air: loudspeaker of " + shared_->stations[index_].name; }

 private:
  void check() const {
    if (shared_->stopped) throw physical::AudioError("the simulated air was stopped");
  }
  std::shared_ptr<SimulatedAir::Shared> shared_;
  std::size_t index_;
};

class AirMicrophone : public physical::AudioSource {
 public:
  AirMicrophone(std::shared_ptr<SimulatedAir::Shared> shared, std::size_t index)
      : shared_(std::move(shared)), index_(index) {}
  std::size_t read(std::span<float> out) override {
    std::unique_lock lock(shared_->mutex);
    auto& recorded = shared_->stations[index_].recorded;
    shared_->changed.wait(lock, [&] { return shared_->stopped || recorded.size() >= out.size(); });
    const std::size_t n = std::min(out.size(), recorded.size());
    std::copy(recorded.begin(), recorded.begin() + static_cast<std::ptrdiff_t>(n), out.begin());
    recorded.erase(recorded.begin(), recorded.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }
  int sample_rate_hz() const override { return shared_->sample_rate_hz; }
  std::string describe() const override { return "simulated air: microphone of " + shared_->stations[index_].name; }

 private:
  std::shared_ptr<SimulatedAir::Shared> shared_;
  std::size_t index_;
};

}  // namespace

SimulatedAir::SimulatedAir(int sample_rate_hz, ChannelConfig config, double block_ms)
    : shared_(std::make_shared<Shared>()) {
  shared_->sample_rate_hz = sample_rate_hz;
  shared_->config = std::move(config);
  if (shared_->config.room.enabled())
    shared_->room = std::make_shared<const RoomModel>(shared_->config.room, sample_rate_hz);
  shared_->block = static_cast<std::size_t>(std::lround(block_ms * sample_rate_hz / 1000.0));
}

SimulatedAir::~SimulatedAir() { stop(); }

SimulatedAir::Station SimulatedAir::add_station(const std::string& name, double position_m) {
  std::lock_guard lock(shared_->mutex);
  if (shared_->running) throw std::logic_error("add every station before start()");
  shared_->stations.push_back({name, position_m, {}, {}, false, nullptr});
  const std::size_t index = shared_->stations.size() - 1;
  return {std::make_unique<AirSpeaker>(shared_, index), std::make_unique<AirMicrophone>(shared_, index)};
}

void SimulatedAir::start() {
  {
    std::lock_guard lock(shared_->mutex);
    auto& stations = shared_->stations;
    const auto& room = shared_->room;
    const bool shoebox = room && room->kind() == RoomModel::Kind::ImageSource;
    // In a shoebox, station p stands at the microphone position moved p metres along x;
    // its own loudspeaker 0.1 m beside its microphone (towards the room's middle).
    std::vector<Point3> at(stations.size()), own_speaker(stations.size());
    if (shoebox) {
      const ShoeboxRoom box = room->shoebox();
      for (std::size_t s = 0; s < stations.size(); ++s) {
        at[s] = room->microphone();
        at[s].x += stations[s].position_m;
        check_inside(box, at[s], "station '" + stations[s].name + "'");
        own_speaker[s] = at[s];
        own_speaker[s].y += at[s].y < box.size_m.y / 2 ? kOwnSpeakerDistanceM : -kOwnSpeakerDistanceM;
      }
    }
    for (std::size_t listener = 0; listener < stations.size(); ++listener) {
      ChannelConfig config = shared_->config;
      config.seed += listener;  // independent noise at each microphone
      auto channel = std::make_unique<AcousticChannel>(shared_->sample_rate_hz, config, room);
      for (std::size_t s = 0; s < stations.size(); ++s) {
        const bool own = s == listener;
        const double d =
            own ? kOwnSpeakerDistanceM
                : std::max(std::abs(stations[s].position_m - stations[listener].position_m), kOwnSpeakerDistanceM);
        if (shoebox) {
          // Reciprocity: between stations A and B the room's one response serves both ways.
          const Point3 from = own ? own_speaker[s] : at[s];
          channel->add_path({distance_m(from, at[listener]), room->between(from, at[listener]), 1, !own});
        } else {
          channel->add_transmitter(d, !own);  // a measured room: its response at 1/d
        }
      }
      stations[listener].channel = std::move(channel);
    }
    shared_->running = true;
  }
  clock_ = std::thread([this] { run(); });
}

void SimulatedAir::stop() {
  {
    std::lock_guard lock(shared_->mutex);
    shared_->stopped = true;
  }
  shared_->changed.notify_all();
  if (clock_.joinable()) clock_.join();
}

void SimulatedAir::mute(const std::string& station, bool muted) {
  std::lock_guard lock(shared_->mutex);
  for (auto& s : shared_->stations) {
    if (s.name == station) {
      s.muted = muted;
      return;
    }
  }
  throw std::invalid_argument("simulated air: no station named '" + station + "'");
}

void SimulatedAir::run() {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration<double>(static_cast<double>(shared_->block) / shared_->sample_rate_hz);
  const auto start = Clock::now();
  const std::size_t max_backlog = static_cast<std::size_t>(kMaxRecordingBacklogS * shared_->sample_rate_hz);
  std::vector<std::vector<float>> played;
  std::vector<float> heard;
  for (long long tick = 1;; ++tick) {
    std::this_thread::sleep_until(start +
                                  std::chrono::duration_cast<Clock::duration>(period * static_cast<double>(tick)));
    std::unique_lock lock(shared_->mutex);
    if (shared_->stopped) return;
    auto& stations = shared_->stations;
    played.assign(stations.size(), std::vector<float>(shared_->block, 0.0f));
    for (std::size_t s = 0; s < stations.size(); ++s) {
      auto& queue = stations[s].to_play;
      const std::size_t n = std::min(queue.size(), shared_->block);
      if (!stations[s].muted)
        std::copy(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(n), played[s].begin());
      queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(n));
    }
    std::vector<std::span<const float>> blocks(played.begin(), played.end());
    for (auto& station : stations) {
      heard.clear();
      station.channel->process(blocks, heard);
      station.recorded.insert(station.recorded.end(), heard.begin(), heard.end());
      if (station.recorded.size() > max_backlog) {
        station.recorded.erase(
            station.recorded.begin(),
            station.recorded.begin() + static_cast<std::ptrdiff_t>(station.recorded.size() - max_backlog));
      }
    }
    lock.unlock();
    shared_->changed.notify_all();
  }
}

}  // namespace dtmf::sim
