// The channel flags dtmfctl simulate and dtmf-room share (protocol/sim/channel_flags.h): what
// each gives, the old spellings, and the combinations refused with the flags named.
#include <gtest/gtest.h>

#include "room_test_support.h"
#include "sim/channel_flags.h"

using namespace dtmf;
using namespace dtmf::sim;

namespace {

// Parses `args` as a program with the channel flags and one positional argument would.
sim::ChannelSetup setup(const std::vector<std::string>& args, double default_reverb_s = 0,
                        std::string* positional = nullptr) {
  CLI::App app{"test"};
  sim::ChannelFlags flags;
  flags.reverb_rt60_s = default_reverb_s;
  sim::add_channel_flags(app, flags);
  std::string file;
  app.add_option("file", file);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  app.parse(reversed);  // CLI11 takes a vector in reverse order
  if (positional) *positional = file;
  return sim::channel_setup(flags);
}

std::string error_of(const std::vector<std::string>& args) {
  try {
    setup(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(ChannelFlags, AnImageSourceRoomWithEveryPartGiven) {
  std::string file;
  const auto s = setup({"--room",
                        "4x5x2.7",
                        "--wall-reflection",
                        "0.8",
                        "--wall-reflection",
                        "floor=125:0.9,8000:0.99",
                        "--mic-at",
                        "1,1.5,0.05",
                        "--speaker-at",
                        "3,4,0.8",
                        "--room-seed",
                        "9",
                        "--mic-response",
                        "cheap-mic",
                        "--whine",
                        "9000:-40",
                        "--whine",
                        "12000:-50",
                        "in.wav",
                        "--radial-speed-mps",
                        "0.22",
                        "--radial-range-m",
                        "1:6",
                        "--clock-ppm",
                        "-3000"},
                       0, &file);
  EXPECT_EQ(file, "in.wav") << "a repeatable flag takes one value each time";
  ASSERT_TRUE(s.config.room.shoebox);
  const ShoeboxRoom& box = *s.config.room.shoebox;
  EXPECT_DOUBLE_EQ(box.size_m.z, 2.7);
  for (Surface w : {kWallX0, kWallX1, kWallY0, kWallY1, kCeiling}) EXPECT_EQ(box.reflection[w], uniform_bands(0.8));
  EXPECT_DOUBLE_EQ(box.reflection[kFloor][0], 0.9);
  EXPECT_DOUBLE_EQ(box.reflection[kFloor][6], 0.99);
  EXPECT_DOUBLE_EQ(box.reflection[kFloor][7], 0.99) << "constant beyond the last point";
  EXPECT_NEAR(box.reflection[kFloor][3], 0.9 + 3.0 / 6 * 0.09, 1e-12) << "1 kHz: halfway on a log axis";
  ASSERT_TRUE(s.config.room.mic_at && s.speaker_at);
  EXPECT_DOUBLE_EQ(s.speaker_at->y, 4);
  EXPECT_EQ(s.config.room.seed, 9u);
  EXPECT_EQ(s.config.mic_response.name, "cheap-mic");
  ASSERT_EQ(s.config.whines.size(), 2u);
  EXPECT_DOUBLE_EQ(s.config.whines[1].level_dbfs, -50);
  EXPECT_DOUBLE_EQ(s.config.motion.speed_mps, 0.22);
  EXPECT_DOUBLE_EQ(s.config.motion.max_distance_m, 6);
  EXPECT_DOUBLE_EQ(s.config.clock_offset_ppm, -3000);
}

TEST(ChannelFlags, TheOldFlagsStillWorkAndTheOldReverberatorStepsAsideForARoom) {
  const auto old = setup({"--distance-m", "7", "--rt60-s", "0.4", "--noise", "pink", "--noise-dbfs", "-45"});
  EXPECT_DOUBLE_EQ(old.distance_m, 7);
  EXPECT_DOUBLE_EQ(old.config.reverb.rt60_s, 0.4);
  EXPECT_EQ(old.config.noise.kind, NoiseKind::Pink);
  const auto simulate = setup({"--distance", "5", "--reverb-rt60", "0.3"});
  EXPECT_DOUBLE_EQ(simulate.config.reverb.rt60_s, 0.3);
  // dtmf-room's default reverberator (0.3 s) is not asked for, so a room replaces it.
  const auto room = setup({"--rir", room_test::rir_path("studio_live_room.wav")}, 0.3);
  EXPECT_EQ(room.config.reverb.rt60_s, 0);
  EXPECT_EQ(setup({}, 0.3).config.reverb.rt60_s, 0.3);
}

TEST(ChannelFlags, CombinationsThatMakeNoSenseAreRefusedNamingTheFlags) {
  EXPECT_NE(error_of({"--rir", "a.wav", "--room", "4x4x3"}).find("--rir and --room"), std::string::npos);
  EXPECT_NE(error_of({"--mic-at", "1,1,1"}).find("give --room too"), std::string::npos);
  EXPECT_NE(
      error_of({"--room", "7x9x3", "--speaker-at", "1,1,1", "--distance", "3"}).find("--distance and --speaker-at"),
      std::string::npos);
  EXPECT_NE(error_of({"--room", "7x9x3", "--reverb-rt60", "0.5"}).find("--reverb-rt60 and a room"), std::string::npos);
  EXPECT_NE(error_of({"--room", "7x9x3", "--room-rt60", "1", "--wall-reflection", "0.8"}).find("only the floor's"),
            std::string::npos);
  EXPECT_EQ(error_of({"--room", "7x9x3", "--room-rt60", "1", "--wall-reflection", "floor=0.95"}), "accepted");
  EXPECT_NE(error_of({"--room", "7x9"}).find("--room: room size '7x9'"), std::string::npos);
  EXPECT_NE(error_of({"--room", "7x9x3", "--wall-reflection", "1.0"}).find("--wall-reflection: "), std::string::npos);
  EXPECT_NE(error_of({"--room", "7x9x3", "--mic-at", "1,1"}).find("--mic-at: position '1,1'"), std::string::npos);
  EXPECT_NE(error_of({"--whine", "loud"}).find("--whine: "), std::string::npos);
  EXPECT_NE(error_of({"--mic-response", "tin-can"}).find("--mic-response: "), std::string::npos);
  EXPECT_NE(error_of({"--radial-range-m", "5:2"}).find("--radial-range-m: "), std::string::npos);
}

TEST(ChannelFlags, AChannelIsMadeFromThemOrRefusedWithTheFlagsToCheck) {
  const auto in_room = setup({"--room", "7x9x3", "--distance", "4"});
  const auto channel = sim::make_channel(in_room, room_test::kRate);
  EXPECT_NE(sim::describe_channel(in_room, *channel).find("loudspeaker 4 m away"), std::string::npos);
  try {
    sim::make_channel(setup({"--room", "7x9x3", "--distance", "30"}), room_test::kRate);
    FAIL() << "a loudspeaker 30 m away in a 9 m room";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at most 8.09 m fit"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--distance"), std::string::npos) << e.what();
  }
}
