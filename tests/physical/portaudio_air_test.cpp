// Physical layer against a real sound server: the PulseAudio "air" of scripts/air.
//
// These tests need a running air and PULSE_SERVER / PULSE_SINK / PULSE_SOURCE exported
// (the ctest fixture in portaudio_air.cmake starts one). One thread plays a command chord
// into the air through PortAudio while another records it, and the robot's listener must
// hear the frame exactly once.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <future>
#include <thread>
#include <vector>

#include "link/seed_sender_path.h"
#include "physical/portaudio_device.h"
#include "profile/link_profile.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"

using namespace dtmf;
using physical::AudioError;
using physical::Direction;
using Clock = std::chrono::steady_clock;

namespace {

double ms_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

class PortAudioAir : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::getenv("PULSE_SERVER")) {
      FAIL() << "no air: run eval \"$(scripts/air start)\" first (ctest does this itself)";
    }
  }
};

}  // namespace

TEST_F(PortAudioAir, SeesThePulseDevicesBothWays) {
  const auto devices = physical::list_audio_devices();
  ASSERT_FALSE(devices.empty());
  std::printf("%s", physical::format_device_list(devices).c_str());
  for (const char* spec : {"pulse", "default"}) {
    for (Direction direction : {Direction::Input, Direction::Output}) {
      EXPECT_NO_THROW({
        const auto device = physical::find_audio_device(spec, direction);
        EXPECT_EQ(device.host_api, "ALSA") << spec;
      }) << spec;
    }
  }
  // The same device by its index.
  const auto pulse = physical::find_audio_device("pulse", Direction::Input);
  EXPECT_EQ(physical::find_audio_device(std::to_string(pulse.index), Direction::Input).name, pulse.name);
}

TEST_F(PortAudioAir, AChordPlayedIntoTheAirIsHeardOnceWithItsBits) {
  const LinkProfile& profile = seed_profile();
  const int rate = profile.sample_rate_hz;
  const link::SeedPlannedFrame planned = link::plan_word(profile, 0b1011'0010'1101);

  // One second of sound: the 0.8 s chord, then silence.
  std::vector<float> sound = signal::synthesize_frame(profile, planned.frame);
  sound.resize(static_cast<std::size_t>(rate), 0.0f);
  std::vector<float> recording(static_cast<std::size_t>(rate * 5 / 2));

  // Both devices are opened here: Pa_Initialize is not thread-safe.
  const Clock::time_point opened = Clock::now();
  const auto input = physical::open_input_device("default", rate);
  const auto output = physical::open_output_device("default", rate);
  std::printf("recording %s\nplaying %s\n", input->describe().c_str(), output->describe().c_str());

  // The player starts once the recording is live (its first read has returned).
  const double hop_ms = 1000.0 * profile.hop_samples() / rate;
  Clock::time_point first_read, play_start, play_end;
  std::promise<void> live;
  std::exception_ptr record_error, play_error;
  std::thread recorder([&] {
    try {
      const std::size_t hop = static_cast<std::size_t>(profile.hop_samples());
      for (std::size_t at = 0; at < recording.size(); at += hop) {
        const std::size_t n = std::min(hop, recording.size() - at);
        input->read(std::span<float>(recording).subspan(at, n));
        if (at == 0) {
          first_read = Clock::now();
          live.set_value();
        }
      }
    } catch (...) {
      record_error = std::current_exception();
      if (first_read == Clock::time_point{}) live.set_value();
    }
  });
  std::thread player([&] {
    try {
      live.get_future().wait();
      if (record_error) return;
      // Kept: the chord sounds 0.3 s into the recording, after silence, as a receiver on the
      // air hears it (and its start is measured against the play time).
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      play_start = Clock::now();
      output->write(sound);
      output->drain();
      play_end = Clock::now();
    } catch (...) {
      play_error = std::current_exception();
    }
  });
  player.join();
  recorder.join();
  if (record_error) std::rethrow_exception(record_error);
  if (play_error) std::rethrow_exception(play_error);
  // A sink still rendering 2 s blocks (no low-latency stream into it) holds every new
  // stream's first samples back for up to 2 s.
  EXPECT_LT(ms_between(opened, first_read), 500) << "the recording took long to start";

  auto listener = signal::chord_listener(profile);
  std::vector<signal::Heard> heard;
  for (const auto& h : listener.feed(recording)) heard.push_back(h);

  ASSERT_EQ(heard.size(), 1u) << "frames heard in 2.5 s of recording";
  EXPECT_EQ(heard[0].symbol, planned.frame);
  // Sample 0 of the recording was captured about one hop before the first read returned.
  const double play_start_ms = ms_between(first_read, play_start) + hop_ms;
  const double latency_ms = heard[0].start_ms - play_start_ms;
  std::printf(
      "played at %.0f ms of the recording, chord found starting at %.0f ms "
      "(latency %.0f ms), passed the debouncer at %.0f ms; write+drain took %.0f ms\n",
      play_start_ms, heard[0].start_ms, latency_ms, heard[0].heard_ms, ms_between(play_start, play_end));
  RecordProperty("latency_ms", static_cast<int>(latency_ms));
  // A late-starting stream (sink still in its first 2 s block) shifts or cuts the chord.
  EXPECT_GT(latency_ms, -100);
  EXPECT_LT(latency_ms, 300) << "the air delays sounds (is the silent stream running?)";
}

TEST_F(PortAudioAir, AnUnknownDeviceNameListsTheChoices) {
  try {
    physical::find_audio_device("no-such-device-xyz", Direction::Input);
    FAIL() << "expected AudioError";
  } catch (const AudioError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no-such-device-xyz"), std::string::npos) << message;
    EXPECT_NE(message.find("choose one of"), std::string::npos) << message;
  }
}
