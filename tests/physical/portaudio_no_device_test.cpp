// Physical layer with no sound server and no sound card: the error must say what to do.
//
// Run with PULSE_SERVER pointing to a socket that does not exist (the ctest entry in
// portaudio_air.cmake does), so that ALSA's pulse plugin cannot reach any server.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "physical/portaudio_device.h"

using namespace dtmf::physical;

TEST(PortAudioNoDevice, OpeningTheDefaultInputSaysHowToGetADevice) {
  const char* server = std::getenv("PULSE_SERVER");
  ASSERT_TRUE(server && std::string(server) == "unix:/nonexistent")
      << "run with PULSE_SERVER=unix:/nonexistent";
  if (!list_audio_devices().empty()) {
    GTEST_SKIP() << "this machine has a sound card:\n" << format_device_list(list_audio_devices());
  }
  try {
    open_input_device("default", 48000);
    FAIL() << "expected AudioError";
  } catch (const AudioError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no audio device found"), std::string::npos) << message;
    EXPECT_NE(message.find("scripts/air start"), std::string::npos) << message;
  }
}

TEST(PortAudioNoDevice, TheDeviceListSaysSoToo) {
  if (!list_audio_devices().empty()) GTEST_SKIP() << "this machine has a sound card";
  EXPECT_NE(format_device_list({}).find("no audio device found"), std::string::npos);
}
