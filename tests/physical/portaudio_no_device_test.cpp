// Physical layer with no sound server and no sound card: the error must say what to do.
//
// Run with PULSE_SERVER pointing to a socket that does not exist (the ctest entry in
// portaudio_air.cmake does). ALSA's pulse plugin then cannot connect, PortAudio drops the
// "pulse" and "default" devices while probing them and sees no device at all, so opening
// fails before any stream is tried. On a machine with a sound card the tests are skipped.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "physical/portaudio_device.h"

using namespace dtmf::physical;

namespace {

class PortAudioNoDevice : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* server = std::getenv("PULSE_SERVER");
    ASSERT_TRUE(server && std::string(server) == "unix:/nonexistent") << "run with PULSE_SERVER=unix:/nonexistent";
    const auto devices = list_audio_devices();
    if (!devices.empty()) {
      GTEST_SKIP() << "this machine has a sound card:\n" << format_device_list(devices);
    }
  }
};

// The message of the NoAudioDevice `open` throws ("" when it throws none, or another error).
template <typename Open>
std::string error_of(Open open) {
  try {
    open();
  } catch (const NoAudioDevice& error) {
    return error.what();
  } catch (const AudioError&) {
  }
  return "";
}

}  // namespace

TEST_F(PortAudioNoDevice, OpeningTheDefaultInputSaysHowToGetADevice) {
  const std::string message = error_of([] { open_input_device("default", 48000); });
  EXPECT_NE(message.find("no audio device found"), std::string::npos) << message;
  EXPECT_NE(message.find("connect a sound card or start a sound server"), std::string::npos) << message;
  EXPECT_NE(message.find("(no input device"), std::string::npos) << message;
  // The layer knows no program: how to work with files instead is each program's to add
  // (common/audio_program.h; tests/agent: dtmf-agent names --audio wav:FILE).
  EXPECT_EQ(message.find("--"), std::string::npos) << message;
  EXPECT_EQ(message.find("scripts/"), std::string::npos) << message;
  EXPECT_NE(message.find("PulseAudio server unix:/nonexistent did not answer"), std::string::npos) << message;
}

TEST_F(PortAudioNoDevice, OpeningTheDefaultOutputOrTheNamedPulseDeviceSaysSoToo) {
  const std::string output = error_of([] { open_output_device("default", 48000); });
  EXPECT_NE(output.find("no audio device found"), std::string::npos) << output;
  EXPECT_NE(output.find("(no output device"), std::string::npos) << output;
  const std::string pulse = error_of([] { find_audio_device("pulse", Direction::Input); });
  EXPECT_NE(pulse.find("no audio device found"), std::string::npos) << pulse;
}
