// dtmf-agent logs every frame it heard, intact or not, to the database.
#include <gtest/gtest.h>

#include "command/word_codec.h"
#include "link/seed_sender_path.h"
#include "physical/wav_file.h"
#include "profile/link_profile.h"
#include "support/run_command.h"
#include "support/seed_audio.h"
#include "temp_database.h"

using namespace dtmf;
using dtmf::test_support::TempDatabase;

TEST(AgentDatabase, EveryReceptionIsLoggedWithItsVerdictAnswerAndEffect) {
  TempDatabase db;
  const LinkProfile& p = seed_profile();
  std::vector<link::SeedPlannedFrame> frames = link::plan_command(p, command::DriveForDuration{50, 1});
  link::SeedPlannedFrame bad = link::plan_word(p, 0x123);
  bad.frame ^= 0x0002;  // fails the CRC
  bad.tones_hz = signal::chord_for(p.words().tones, bad.frame);
  frames.push_back(bad);
  const std::string wav = ::testing::TempDir() + "/agent-db-" + std::to_string(::getpid()) + ".wav";
  physical::write_wav_file(wav, test_support::seed_audio(p, frames), p.sample_rate_hz);

  const auto r = test_support::run_command(std::string(DTMF_AGENT_PATH) + " --audio wav:" + wav +
                                           " --cmd-vel log --host robot-under-test --spill-file " + wav +
                                           ".spill --db " + db.url());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM receptions WHERE host = 'robot-under-test'"), 4);
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM receptions WHERE crc_ok AND reply = 'ack'"), 3);
  EXPECT_EQ(db.query<long>("SELECT count(*) FROM receptions WHERE NOT crc_ok AND reply = 'nack' AND word IS NULL"), 1);
  EXPECT_EQ(db.query<std::string>("SELECT string_agg(event, ',' ORDER BY heard_at) FROM receptions WHERE crc_ok"),
            "reset,mode_selected,command");
  EXPECT_DOUBLE_EQ(db.query<double>("SELECT linear_mps FROM receptions WHERE event = 'command'"), 0.11);
  EXPECT_EQ(db.query<std::string>("SELECT command FROM receptions WHERE event = 'command'"),
            command::describe(command::quantised(command::DriveForDuration{50, 1})));
  EXPECT_EQ(db.query<std::string>("SELECT frame_bits(frame, frame_width) FROM receptions WHERE NOT crc_ok"),
            reliability::bit_string(bad.frame));
}
