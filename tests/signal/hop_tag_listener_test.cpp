// Signal layer, fast profile: the keyed sender's tag-chord ear (signal/hop_tag_listener.h)
// hears the robot's tag chord right after the sender's own frame ends, 20 dB louder at its
// microphone, at the clock offsets it reads, and from a robot 3 m away; noise and the frame
// alone spell no tag.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "command/command.h"
#include "command/random_command.h"
#include "link/link.h"
#include "reliability/tag_chord.h"
#include "security/link_key.h"
#include "signal/hop_synthesizer.h"
#include "signal/hop_tag_listener.h"
#include "sim/acoustic_channel.h"

using namespace dtmf;

namespace {

const LinkProfile& p = fast_profile();

link::LinkOptions keyed() {
  std::array<unsigned char, security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(0x21 ^ (13 * i));
  link::LinkOptions o;
  o.key = security::LinkKey::from_bytes(bytes);
  return o;
}

std::vector<signal::HeardTagChord> heard(const std::vector<float>& audio) {
  signal::HopTagListener ear(p);
  std::vector<signal::HeardTagChord> got;
  for (std::size_t at = 0; at < audio.size(); at += 240) {
    for (const auto& h :
         ear.feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(240, audio.size() - at))))
      got.push_back(h);
  }
  return got;
}

struct Spelled {
  int spelling = 0;  // readings that spell the tag awaited
  int readings = 0;
};

struct Air {
  double ppm = 0;  // the robot's clock against the sender's
  bool with_answer = true;
  std::string room;                // a measured room (bench/rirs), or free field
  double own_db = 0;               // the sender's own loudspeaker this much louder
  double robot_m = 1;              // the robot's distance
  std::uint32_t command_seed = 0;  // 0: Stop; else a random command
};

// The sender's frame from 0.1 m and the robot's answer from `robot_m`, each through the room if
// any, the answer as late as the sound's way to the robot and back makes it.
Spelled frame_then_answer(const Air& air_case) {
  const double ppm = air_case.ppm;
  const bool with_answer = air_case.with_answer;
  const auto sender = link::make_link(p, keyed());
  const auto robot = link::make_link(p, keyed());
  std::mt19937_64 rng(air_case.command_seed);
  const auto planned =
      sender->plan(air_case.command_seed == 0 ? command::Command{command::Stop{}} : command::random_command(rng));
  const link::TransmitFrame& f = planned.back();
  std::vector<float> own(4800, 0.0f), answer;
  const auto own_gain = static_cast<float>(std::pow(10.0, air_case.own_db / 20));
  for (const float x : f.audio) own.push_back(own_gain * x);
  own.resize(own.size() + 9600, 0.0f);
  // The free field delays the answer on its way back; a measured room's response is the same
  // for both paths, so the way back is added here too.
  const double flight_s = air_case.robot_m / sim::kSpeedOfSoundMps * (air_case.room.empty() ? 1 : 2);
  answer.assign(4800 + f.audio.size() + static_cast<std::size_t>(flight_s * p.sample_rate_hz), 0.0f);
  if (with_answer) {
    const auto a = robot->answer_audio(link::intact_reception(f));  // 2 ms after the frame ends
    answer.insert(answer.end(), a.begin(), a.end());
  }
  answer.resize(own.size(), 0.0f);
  // The sender's microphone shares its own loudspeaker's clock; the robot's runs `ppm` off.
  sim::ChannelConfig own_air, robot_air;
  own_air.noise = sim::parse_noise("pink", -50);
  robot_air.clock_offset_ppm = ppm;
  if (!air_case.room.empty())
    own_air.room.rir_file = robot_air.room.rir_file = std::string(DTMF_RIR_DIR) + "/" + air_case.room + ".wav";
  sim::AcousticChannel own_path(p.sample_rate_hz, own_air), robot_path(p.sample_rate_hz, robot_air);
  own_path.add_transmitter(0.1, false);
  robot_path.add_transmitter(air_case.robot_m, false);
  std::vector<float> mic, from_robot;
  own_path.process(own, mic);
  robot_path.process(answer, from_robot);
  mic.resize(std::min(mic.size(), from_robot.size()));
  for (std::size_t i = 0; i < mic.size(); ++i) mic[i] += from_robot[i];
  Spelled s;
  for (const auto& h : heard(mic)) {
    ++s.readings;
    s.spelling += reliability::spells_tag_chord(h.reading, f.answer_tag, f.sent_tones) ? 1 : 0;
  }
  return s;
}

}  // namespace

class HopTagListenerOffset : public ::testing::TestWithParam<double> {};

TEST_P(HopTagListenerOffset, TheTagIsHeardRightAfterTheSendersOwnLouderFrame) {
  const Spelled s = frame_then_answer(Air{GetParam(), true, "", 0});
  EXPECT_GE(s.spelling, 1) << "the tag was heard at " << GetParam() << " ppm";
}

INSTANTIATE_TEST_SUITE_P(Ppm, HopTagListenerOffset, ::testing::Values(-1500.0, -600.0, 0.0, 900.0, 1500.0));

TEST(HopTagListener, TheFrameAloneAndNoiseSpellNoTagAndNoiseIsReadAtMostOnceAHop) {
  const Spelled alone = frame_then_answer(Air{0, false, "", 0});
  EXPECT_EQ(alone.spelling, 0);
  // Loud white noise: a band's strongest risen bin often stands 3 dB over its median, so noise
  // gives readings; the forgery bound (docs/security.md) counts one a hop, and none spells a tag.
  std::vector<float> noise(48000 * 10);
  std::mt19937 rng(5);
  std::normal_distribution<float> gauss(0.0f, 0.1f);
  for (float& x : noise) x = gauss(rng);
  const auto got = heard(noise);
  const auto hops = static_cast<long long>(noise.size()) / p.hops().hop_samples;
  std::printf("[ figures  ] white noise, 10 s: %zu readings in %lld hops\n", got.size(), hops);
  EXPECT_LE(static_cast<long long>(got.size()), hops);
  for (std::size_t i = 1; i < got.size(); ++i) EXPECT_GT(got[i].window, got[i - 1].window);
  const reliability::TagChordSymbols tag = reliability::tag_chord_symbols(reliability::TagBytes{7, 1, 9}, {});
  for (const auto& h : got) EXPECT_FALSE(reliability::spells_tag_chord(h.reading, tag, {}));
}

// In the smoking room (RT60 0.74 s) too, with the sender's loudspeaker 10 dB louder than the
// robot's on top of its 0.1 m (a margin: the room's reverberation of the frame then stands
// 10 dB over the answer's): the frame's own tones are set aside and its tail does not rise.
TEST(HopTagListener, InTheSmokingRoomBesideTheSendersLouderFrameTheTagIsHeard) {
  for (const double ppm : {-900.0, 0.0, 600.0})
    EXPECT_GE(frame_then_answer(Air{ppm, true, "smoking_room", 10}).spelling, 1) << ppm << " ppm";
}

// A robot 3 m away answers 17.5 ms later than one beside the sender: the window a chord
// before the tag's first then holds the cut-off end of the sender's own frame, 20 dB louder
// and spread over every bin. Against that window no tone of the tag rose; against the quietest
// earlier window, one wholly inside the frame's last chord, they did. In the club hall
// (RT60 2.24 s) and the seminar room, 24 frames each.
TEST(HopTagListener, ARobotThreeMetresAwayIsHeardBesideTheSendersOwnFrame) {
  for (const char* room : {"club_hall", "seminar_room_clap"}) {
    int heard = 0;
    for (std::uint32_t seed = 1; seed <= 24; ++seed)
      heard += frame_then_answer(Air{0, true, room, 0, 3, seed}).spelling >= 1 ? 1 : 0;
    std::printf("[ figures  ] %s, 3 m: %d of 24 tags heard\n", room, heard);
    EXPECT_EQ(heard, 24) << room;
  }
}

// Every band of a chord synthesized alone is read at its own value, at the middle offset.
TEST(HopTagListener, EveryBandReadsItsValue) {
  for (int shift = 0; shift < 32; shift += 7) {
    reliability::TagChordSymbols symbols{};
    for (std::size_t k = 0; k < symbols.size(); ++k) symbols[k] = static_cast<std::uint8_t>((3 * k + shift) % 32);
    std::vector<float> audio(4800, 0.0f);
    const auto chord = signal::synthesize_tag_chord(p, symbols);
    audio.insert(audio.end(), chord.begin(), chord.end());
    audio.resize(audio.size() + 4800, 0.0f);
    const auto got = heard(audio);
    ASSERT_FALSE(got.empty()) << shift;
    int best = 0;
    for (const auto& h : got) best = std::max(best, reliability::tag_chord_matches(h.reading, symbols, {}));
    EXPECT_EQ(best, 16) << shift;
  }
}
