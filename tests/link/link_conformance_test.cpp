// Every link of every profile, made by make_link with and without a key, through the whole
// round: plan -> render -> a channel -> the robot's receiver -> its answer -> the channel
// back -> the sender's ear -> answers(). In a clean channel and through the measured seminar
// room (both ways). A link that can carry a MAC confirms under a key; the seed's, which
// cannot, is refused by a robot with a key (and NACKed), and let in when the robot accepts
// unauthenticated frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <string>

#include "command/command.h"
#include "link/answer_wait.h"
#include "link/link.h"
#include "sim/acoustic_channel.h"
#include "sim/room_model.h"
#include "support/third_profile.h"

using namespace dtmf;

namespace {

enum class Keys { None, Both, RobotLetsUnauthenticatedIn };

struct Case {
  const LinkProfile* profile;
  Keys keys;
  bool room;
};

std::string case_name(const Case& c) {
  return c.profile->name +
         (c.keys == Keys::None   ? "_unkeyed"
          : c.keys == Keys::Both ? "_keyed"
                                 : "_keyed_lenient") +
         (c.room ? "_seminar_room" : "_clean");
}
// gtest names take letters, digits and underscores: a profile called "fast-high" reads fast_high.
std::string name_of(const ::testing::TestParamInfo<Case>& info) {
  std::string name = case_name(info.param);
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}
// ctest's test names show the parameter: its name, not its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << case_name(c); }

std::vector<Case> cases() {
  test_support::third_profile();  // a profile the tests add, which the links must carry as they carry their own
  std::vector<Case> out;
  for (const LinkProfile* p : all_profiles()) {
    for (Keys k : {Keys::None, Keys::Both, Keys::RobotLetsUnauthenticatedIn}) {
      for (bool room : {false, true}) out.push_back({p, k, room});
    }
  }
  return out;
}

// Sound from one side to the other: the seminar room (measured) at 1 m with quiet pink noise,
// or nothing but a little white noise. The listener hears 100 ms of the air before the sound
// comes, as a live one does (a listener learns what the air holds before a reply).
std::vector<float> through(const LinkProfile& profile, bool room, const std::vector<float>& sound, std::uint64_t seed) {
  sim::ChannelConfig config;
  config.seed = seed;
  config.noise = room ? sim::parse_noise("pink", -50) : sim::parse_noise("white", -80);
  std::shared_ptr<const sim::RoomModel> model;
  if (room) {
    config.room.rir_file = std::string(DTMF_RIR_DIR) + "/seminar_room_clap.wav";
    model = std::make_shared<const sim::RoomModel>(config.room, profile.sample_rate_hz);
  }
  auto channel = model ? std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config, model)
                       : std::make_unique<sim::AcousticChannel>(profile.sample_rate_hz, config);
  channel->add_transmitter(1.0);
  const auto lead = static_cast<std::size_t>(profile.sample_rate_hz / 10);
  std::vector<float> padded(lead, 0.0f);
  padded.insert(padded.end(), sound.begin(), sound.end());
  padded.resize(padded.size() + static_cast<std::size_t>(profile.sample_rate_hz), 0.0f);  // a second to ring out
  std::vector<float> heard;
  channel->process(padded, heard);
  return heard;
}

}  // namespace

class LinkConformance : public ::testing::TestWithParam<Case> {};

TEST_P(LinkConformance, PlanRenderReceiveAnswerAndHearTheAnswer) {
  const Case& c = GetParam();
  const LinkProfile& profile = *c.profile;
  link::LinkOptions sender_options, robot_options;
  // Fixed key, sequence numbers and noise: the same audio on every run.
  sender_options.first_sequence = 5;
  if (c.keys != Keys::None) {
    std::array<unsigned char, security::kKeyBytes> bytes{};
    const char* fill = std::getenv("DTMF_CONFORMANCE_KEY_FILL");  // stress runs vary it
    for (std::size_t i = 0; i < bytes.size(); ++i)
      bytes[i] = static_cast<unsigned char>((fill ? std::atoi(fill) : 3) + 7 * i);
    const auto key = security::LinkKey::from_bytes(bytes);
    sender_options.key = robot_options.key = key;
    robot_options.accept_unauthenticated = c.keys == Keys::RobotLetsUnauthenticatedIn;
  }
  const auto sender = link::make_link(profile, sender_options);
  const auto robot = link::make_link(profile, robot_options);
  const bool authenticated = c.keys != Keys::None && sender->can_authenticate();
  const bool refused = c.keys == Keys::Both && !sender->can_authenticate();

  const command::Command drive = command::DriveForDuration{40, 2};
  const auto receiver = robot->receiver();
  const auto ear = sender->answer_listener();
  std::uint64_t seed = 1;
  // Frame by frame, as a stop-and-wait sender: each frame, then its answer heard.
  const std::vector<link::TransmitFrame> frames = sender->plan(drive);
  for (const link::TransmitFrame& frame : frames) {
    EXPECT_EQ(frame.authenticated, authenticated);
    const std::vector<link::TransmitFrame> one{frame};
    const auto heard = through(profile, c.room, sender->render(one), seed++);
    std::vector<link::Reception> receptions;
    for (std::size_t at = 0; at < heard.size(); at += 1024) {
      for (const auto& r :
           receiver->feed(std::span<const float>(heard).subspan(at, std::min<std::size_t>(1024, heard.size() - at)))) {
        receptions.push_back(r);
      }
    }
    ASSERT_EQ(receptions.size(), 1u) << "one verdict for the frame";
    const link::Reception& r = receptions.front();
    EXPECT_TRUE(r.intact);
    EXPECT_EQ(r.bits, frame.bits);
    EXPECT_EQ(r.authenticated, authenticated);
    if (refused) {
      EXPECT_EQ(r.event, link::ReceptionEvent::Refused);
      EXPECT_EQ(r.refusal, link::RefusalReason::Authentication);
      EXPECT_FALSE(r.command);
    } else {
      EXPECT_TRUE(r.acknowledged()) << r.detail;
    }
    const auto answer_heard = through(profile, c.room, robot->answer_audio(r), seed++);
    std::vector<link::Answer> answers;
    const auto block = static_cast<std::size_t>(sender->answer_block_samples());
    for (std::size_t at = 0; at < answer_heard.size(); at += block) {
      for (const auto& a :
           ear->feed(std::span<const float>(answer_heard).subspan(at, std::min(block, answer_heard.size() - at)))) {
        answers.push_back(a);
      }
    }
    // The sender takes the first answer to its frame (a reply's first window, straddling its
    // start, may read a tone wrong: a guess of its budget, that answers nothing).
    link::AnswerWait wait(*sender, frame);
    const auto answered =
        std::find_if(answers.begin(), answers.end(), [&](const link::Answer& a) { return wait.answered_by(a); });
    ASSERT_NE(answered, answers.end()) << "no answer to this frame among " << answers.size();
    EXPECT_EQ(answered->ack, !refused);
    for (const auto& a : answers) EXPECT_EQ(a.ack, !refused) << "every answer heard is the robot's";
    if (answered->ack) sender->confirmed(frame);
    if (refused) return;  // the seed's first word, refused: nothing more goes through
    if (&frame == &frames.back()) {
      ASSERT_TRUE(r.command) << "the last frame completes the command";
      EXPECT_EQ(command::describe(*r.command), command::describe(sender->as_received(drive)));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllProfiles, LinkConformance, ::testing::ValuesIn(cases()), name_of);
