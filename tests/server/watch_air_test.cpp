// WatchAir through the whole system: real gRPC on loopback, the transmitter, a simulated
// room, the robot agent. A watcher sees a command's frame go on the air, the robot's answer
// heard and taken, and the command's end, on the microphone's clock; columns of the spectrum
// at its rate and resolution, louder while a frame sounds; and a watcher that does not read
// loses columns, is told so, and holds the sender up not at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "air_fanout.h"
#include "link/link.h"
#include "live_system.h"
#include "support/wait_for.h"

using namespace dtmf;
using namespace std::chrono_literals;
using test_support::LiveSystem;
using test_support::read_stream;
using test_support::wait_until;

namespace {

v1::DriveRequest fast_drive(double speed) {
  v1::DriveRequest r;
  r.set_speed_percent(speed);
  r.set_duration_s(1);
  r.mutable_options()->set_profile("fast");
  return r;
}

// A WatchAir stream read on a thread of its own until `enough` holds of what it read.
class Watcher {
 public:
  Watcher(LiveSystem& system, v1::WatchAirRequest request,
          std::function<bool(const std::vector<v1::WatchAirResponse>&)> enough)
      : stub_(system.client()) {
    reader_ = stub_->WatchAir(&context_, request);
    thread_ = std::thread([this, enough] {
      v1::WatchAirResponse m;
      while (reader_->Read(&m)) {
        std::lock_guard lock(mutex_);
        read_.push_back(m);
        if (enough(read_)) break;
      }
      context_.TryCancel();
      status_ = reader_->Finish();
    });
  }
  ~Watcher() {
    context_.TryCancel();
    if (thread_.joinable()) thread_.join();
  }
  std::vector<v1::WatchAirResponse> read() {
    std::lock_guard lock(mutex_);
    return read_;
  }
  void join() { thread_.join(); }
  grpc::Status status() const { return status_; }

 private:
  std::unique_ptr<v1::TeleopService::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<v1::WatchAirResponse>> reader_;
  std::mutex mutex_;
  std::vector<v1::WatchAirResponse> read_;
  grpc::Status status_;
  std::thread thread_;
};

bool has_ended(const std::vector<v1::WatchAirResponse>& read) {
  return std::any_of(read.begin(), read.end(), [](const auto& m) { return m.has_command_ended(); });
}

}  // namespace

TEST(WatchAir, AWatcherSeesAFrameItsAnswerAndItsEnd) {
  LiveSystem system;
  Watcher watcher(system, {}, has_ended);
  ASSERT_TRUE(wait_until([&] { return system.air_watchers() == 1; }, 5s));
  auto client = system.client();
  const auto drive =
      read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, fast_drive(40)); });
  ASSERT_TRUE(drive.status.ok()) << drive.status.error_message();
  ASSERT_TRUE(wait_until([&] { return has_ended(watcher.read()); }, 5s));
  const auto read = watcher.read();
  const auto find = [&](auto has) { return std::find_if(read.begin(), read.end(), has); };
  const auto played = find([](const auto& m) { return m.has_frame_played(); });
  const auto heard = find([](const auto& m) { return m.has_answer_heard() && m.answer_heard().ack(); });
  const auto answered = find([](const auto& m) { return m.has_frame_answered(); });
  const auto ended = find([](const auto& m) { return m.has_command_ended(); });
  ASSERT_NE(played, read.end());
  ASSERT_NE(heard, read.end());
  ASSERT_NE(answered, read.end());
  const v1::FramePlayed& f = played->frame_played();
  ASSERT_EQ(f.robots_size(), 1);
  EXPECT_EQ(f.robots(0), "robot");
  EXPECT_EQ(f.kind(), "command");
  EXPECT_EQ(f.profile(), "fast");
  EXPECT_EQ(f.attempt(), 1u);
  ASSERT_TRUE(f.has_sequence());
  EXPECT_EQ(f.sequence(), drive.responses.back().progress().sequence());
  EXPECT_EQ(f.command_id(), drive.responses.back().progress().command_id());
  EXPECT_GT(f.chord_ms(), 0);
  // The answer, on the microphone's clock, after the frame began and within its ACK timeout.
  EXPECT_EQ(heard->answer_heard().sequence(), f.sequence());
  EXPECT_EQ(heard->answer_heard().robot(), "robot");
  EXPECT_GT(heard->answer_heard().level_dbfs(), -90);
  EXPECT_GT(heard->audio_ms(), played->audio_ms());
  EXPECT_LT(heard->audio_ms(), played->audio_ms() + 600);
  EXPECT_EQ(answered->frame_answered().answer(), "ack");
  EXPECT_EQ(answered->frame_answered().command_id(), f.command_id());
  EXPECT_GT(answered->frame_answered().response_time_ms(), 0);
  EXPECT_EQ(ended->command_ended().outcome(), "confirmed");
  EXPECT_GT(played->time_unix_ms(), 0);
  for (const auto& m : read) EXPECT_EQ(m.dropped_events(), 0u);
}

TEST(WatchAir, SpectrumColumnsComeAtTheRateAskedAndShowTheFrame) {
  LiveSystem system;
  v1::WatchAirRequest request;
  request.set_spectrum(true);
  request.set_columns_per_s(20);
  request.set_bins(64);
  Watcher watcher(system, request, has_ended);
  ASSERT_TRUE(wait_until([&] { return system.air_watchers() == 1; }, 5s));
  // Half a second of the room's floor before the frame sounds.
  ASSERT_TRUE(wait_until([&] { return watcher.read().size() >= 10; }, 5s));
  auto client = system.client();
  ASSERT_TRUE(read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) {
                return client->Drive(&c, fast_drive(30));
              }).status.ok());
  ASSERT_TRUE(wait_until([&] { return has_ended(watcher.read()); }, 5s));
  std::vector<v1::WatchAirResponse> columns;
  for (const auto& m : watcher.read())
    if (m.has_spectrum()) columns.push_back(m);
  ASSERT_GE(columns.size(), 10u);
  const double span_ms = columns.back().audio_ms() - columns.front().audio_ms();
  EXPECT_NEAR((columns.size() - 1) * 1000.0 / span_ms, 20, 2) << columns.size() << " columns in " << span_ms << " ms";
  float quietest = 0, loudest = -200;
  for (const auto& c : columns) {
    ASSERT_EQ(c.spectrum().level_dbfs_size(), 64);
    EXPECT_DOUBLE_EQ(c.spectrum().low_hz(), server::kSpectrumLowHz);
    const float top = *std::max_element(c.spectrum().level_dbfs().begin(), c.spectrum().level_dbfs().end());
    quietest = std::min(quietest, top);
    loudest = std::max(loudest, top);
  }
  EXPECT_GT(loudest - quietest, 20) << "a frame's tones stand over the room's floor";
}

TEST(WatchAir, AWatcherThatDoesNotReadLosesColumnsAndHoldsNothingUp) {
  LiveSystem system;
  // A client whose transport takes little ahead of what it reads: what the server cannot
  // write piles up in the watcher's queue, where the oldest go.
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  args.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 16 * 1024);
  auto stub = v1::TeleopService::NewStub(grpc::CreateCustomChannel("127.0.0.1:" + std::to_string(system.port()),
                                                                   grpc::InsecureChannelCredentials(), args));
  grpc::ClientContext context;
  v1::WatchAirRequest request;
  request.set_spectrum(true);
  request.set_columns_per_s(50);
  request.set_bins(512);  // 2 kB a column: 100 kB a second
  auto reader = stub->WatchAir(&context, request);
  ASSERT_TRUE(wait_until([&] { return system.air_watchers() == 1; }, 5s));
  // Not read for 3 s (the time is the behaviour: 300 kB of columns, far past what its
  // transport takes ahead), while the sender's commands go as ever.
  auto client = system.client();
  const auto until = std::chrono::steady_clock::now() + 3s;
  int drives = 0;
  for (double speed = 20; std::chrono::steady_clock::now() < until; speed = speed < 60 ? speed + 10 : 20) {
    ++drives;
    const auto drive =
        read_stream<v1::DriveResponse>([&](grpc::ClientContext& c) { return client->Drive(&c, fast_drive(speed)); });
    ASSERT_TRUE(drive.status.ok()) << drive.status.error_message();
    EXPECT_EQ(drive.responses.back().progress().event(), v1::FRAME_EVENT_CONFIRMED);
    for (const auto& r : drive.responses) {
      if (r.progress().event() == v1::FRAME_EVENT_ACK) {
        EXPECT_LT(r.progress().response_time_ms(), 500);
      }
    }
  }
  std::uint64_t dropped_columns = 0, dropped_events = 0;
  int frames_played = 0;
  v1::WatchAirResponse m;
  while (reader->Read(&m)) {
    dropped_columns += m.dropped_columns();
    dropped_events += m.dropped_events();
    frames_played += m.has_frame_played();
    if (frames_played == drives) break;
  }
  context.TryCancel();
  reader->Finish();
  EXPECT_GT(dropped_columns, 0u) << "it read too slowly, and was told";
  EXPECT_EQ(dropped_events, 0u) << "columns go before events";
  EXPECT_EQ(frames_played, drives);
}

TEST(WatchAir, RefusesWhatItCannotServe) {
  LiveSystem system;
  auto client = system.client();
  const auto refused = [&](v1::WatchAirRequest request) {
    return read_stream<v1::WatchAirResponse>([&](grpc::ClientContext& c) { return client->WatchAir(&c, request); });
  };
  v1::WatchAirRequest fine;
  fine.set_spectrum(true);
  fine.set_bins(513);
  auto r = refused(fine);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("bins 513"), std::string::npos) << r.status.error_message();
  v1::WatchAirRequest fast;
  fast.set_spectrum(true);
  fast.set_columns_per_s(60);
  r = refused(fast);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("columns_per_s"), std::string::npos) << r.status.error_message();
  v1::WatchAirRequest nobody;
  nobody.set_robot("nobody");
  r = refused(nobody);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("nobody"), std::string::npos) << r.status.error_message();
  v1::WatchAirRequest hostile;
  hostile.set_robot("a\nb");
  r = refused(hostile);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(r.status.error_message().find('\n'), std::string::npos) << "echoed escaped";
}

TEST(WatchAir, SixteenWatchersAtMostAndAllEndWhenTheServerStops) {
  auto system = std::make_unique<LiveSystem>();
  std::vector<std::unique_ptr<Watcher>> watchers;
  for (std::size_t i = 0; i < server::kMaxWatchers; ++i)
    watchers.push_back(std::make_unique<Watcher>(*system, v1::WatchAirRequest{}, [](const auto&) { return false; }));
  ASSERT_TRUE(wait_until([&] { return system->air_watchers() == server::kMaxWatchers; }, 10s));
  auto client = system->client();
  const auto one_more = read_stream<v1::WatchAirResponse>(
      [&](grpc::ClientContext& c) { return client->WatchAir(&c, v1::WatchAirRequest{}); });
  EXPECT_EQ(one_more.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  system.reset();  // the server stops: every stream ends
  for (auto& w : watchers) {
    w->join();
    EXPECT_NE(w->status().error_code(), grpc::StatusCode::OK);
  }
  watchers.clear();
}

TEST(WatchAir, TheSpectrumSpansEveryProfilesTones) {
  // The seed's answers are chords of their own, heard between these.
  const auto& seed_ears = seed_profile().words().sender_detector;
  EXPECT_GE(seed_ears.bandpass_low_hz, server::kSpectrumLowHz);
  EXPECT_LE(seed_ears.bandpass_high_hz, server::kSpectrumHighHz);
  for (const LinkProfile* profile : all_profiles()) {
    auto links = link::make_links({});
    for (auto& l : links) {
      if (&l->profile() != profile) continue;
      for (std::uint64_t seed = 0; seed < 20; ++seed) {
        for (double hz : l->random_frame(seed).tones_hz) {
          EXPECT_GE(hz, server::kSpectrumLowHz) << profile->name;
          EXPECT_LE(hz, server::kSpectrumHighHz) << profile->name;
        }
      }
    }
  }
}
