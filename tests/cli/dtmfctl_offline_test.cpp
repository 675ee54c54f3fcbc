// dtmfctl's offline subcommands, run as a user runs them: the real binary, its output and
// exit codes.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "physical/wav_file.h"
#include "support/run_command.h"

namespace fs = std::filesystem;

namespace {

using Result = dtmf::test_support::CommandResult;
using dtmf::test_support::json_lines;
using dtmf::test_support::whole_json_lines;

Result run(const std::string& args) { return dtmf::test_support::run_command(std::string(DTMFCTL_PATH) + " " + args); }

class Dtmfctl : public ::testing::Test {
 protected:
  fs::path dir_ = fs::path(::testing::TempDir()) / ("dtmfctl-" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

}  // namespace

TEST_F(Dtmfctl, EncodeWordPrintsTheSeedsExampleFrame) {
  const Result r = run("encode --json --word 2861");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto lines = json_lines(r.out);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["word"], 2861);
  EXPECT_EQ(lines[0]["frame"], "1011001011011101");
  EXPECT_EQ(lines[0]["crc"], "1101");
  ASSERT_EQ(lines[0]["tones_hz"].size(), 4u);
  EXPECT_NEAR(lines[0]["tones_hz"][0].get<double>(), 4500 + 11 * 2500.0 / 15, 1e-6);
}

// With --json, standard output is JSON Lines and nothing else, whatever the subcommand logs
// (a keyed encode once logged "key ... counters in ..." there, and jq failed on it).
TEST_F(Dtmfctl, EveryJsonCommandPrintsJsonOnly) {
  const std::string key = path("link.key");
  const std::string state = " --state-dir " + path("state");
  const std::vector<std::string> commands = {
      "keygen " + key,
      "encode --word 2861",
      "encode --key " + key + state + " --profile fast drive --speed 10",
      "encode --profile fast --wav " + path("f.wav") + " sequence",
      "encode --key " + key + state + " --profile fast --wav " + path("k.wav") + " stop",
      "decode --profile fast " + path("f.wav"),
      "decode --key " + key + " --profile fast " + path("k.wav"),
      "simulate --profile fast " + path("f.wav") + " " + path("heard.wav") + " --distance 2",
      "decode --profile fast " + path("heard.wav"),
  };
  for (const auto& command : commands) {
    const Result r = dtmf::test_support::run_command(std::string(DTMFCTL_PATH) + " --json " + command, false);
    EXPECT_EQ(r.exit_code, 0) << command << ": " << r.out;
    std::vector<nlohmann::json> lines;
    EXPECT_NO_THROW(lines = whole_json_lines(r.out)) << command << ":\n" << r.out;
    EXPECT_FALSE(lines.empty()) << command;
  }
}

TEST_F(Dtmfctl, EncodeThenDecodeGivesBackTheSameFramesInOrder) {
  const Result enc = run("encode --json --wav " + path("x.wav") + " drive --speed 50 --duration 3");
  ASSERT_EQ(enc.exit_code, 0) << enc.out;
  const Result dec = run("decode --json " + path("x.wav"));
  ASSERT_EQ(dec.exit_code, 0) << dec.out;
  const auto sent = json_lines(enc.out), heard = json_lines(dec.out);
  ASSERT_EQ(sent.size(), 3u);
  ASSERT_EQ(heard.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(heard[i]["frame"], sent[i]["frame"]);
    EXPECT_EQ(heard[i]["word"], sent[i]["word"]);
    EXPECT_EQ(heard[i]["tones_hz"], sent[i]["tones_hz"]);
    EXPECT_TRUE(heard[i]["crc_ok"].get<bool>());
    EXPECT_NEAR(heard[i]["t_ms"].get<double>(), sent[i]["t_ms"].get<double>(), 50);
  }
  EXPECT_EQ(heard[2]["event"]["kind"], "command");
  EXPECT_EQ(heard[2]["event"]["command"], "drive_for_duration speed=50.0% duration=2.97s");
}

TEST_F(Dtmfctl, TheFastProfileEncodesAWholeCommandPerFrameAndDecodesItBackThroughARoom) {
  const Result enc = run("encode --profile fast --json --wav " + path("f.wav") + " sequence");
  ASSERT_EQ(enc.exit_code, 0) << enc.out;
  const auto sent = json_lines(enc.out);
  ASSERT_EQ(sent.size(), 27u) << "one frame per command of the seed's sequence";
  EXPECT_EQ(sent[0]["frame"].get<std::string>().size(), 50u) << "address, sequence, command, CRC-16";
  EXPECT_EQ(sent[0]["tones_hz"].size(), 16u) << "two chords of eight tones";
  const Result sim = run("simulate --profile fast " + path("f.wav") + " " + path("g.wav") +
                         " --distance 5 --noise pink --noise-dbfs -45 --reverb-rt60 0.3");
  ASSERT_EQ(sim.exit_code, 0) << sim.out;
  const Result dec = run("decode --profile fast --json " + path("g.wav"));
  ASSERT_EQ(dec.exit_code, 0) << dec.out;
  const auto heard = json_lines(dec.out);
  ASSERT_EQ(heard.size(), sent.size()) << dec.out;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_TRUE(heard[i]["crc_ok"].get<bool>()) << i;
    EXPECT_EQ(heard[i]["frame"], sent[i]["frame"]) << i;
    EXPECT_EQ(heard[i]["sequence"], sent[i]["sequence"]) << i;
    EXPECT_EQ(heard[i]["what"], sent[i]["command"]) << i;
  }
  const Result word = run("encode --profile fast --word 5");
  EXPECT_EQ(word.exit_code, 2);
  EXPECT_NE(word.out.find("sends whole commands, not words"), std::string::npos) << word.out;
}

// A recording that stops 100 ms after a damaged frame (as `encode` leaves it) still gets the
// frame's verdict: the robot would have gone on listening, and its NACK comes 133 ms after the
// frame's first failed window. The frame: one command's first chord, another's second.
TEST_F(Dtmfctl, ADamagedFrameAtTheEndOfARecordingIsStillReported) {
  ASSERT_EQ(run("encode --profile fast --wav " + path("a.wav") + " drive --speed 50 --duration 2").exit_code, 0);
  ASSERT_EQ(run("encode --profile fast --wav " + path("b.wav") + " turn --rotation 30").exit_code, 0);
  const auto read = [&](const std::string& name) {
    dtmf::physical::WavFileSource source(path(name), 48000);
    std::vector<float> audio, block(4096);
    while (const std::size_t got = source.read(block)) audio.insert(audio.end(), block.begin(), block.begin() + got);
    return audio;
  };
  const std::vector<float> a = read("a.wav"), b = read("b.wav");
  constexpr std::size_t kChord = 2460, kFrame = 2 * kChord, kAfter = 4800;
  ASSERT_EQ(a.size(), kFrame + kAfter) << "one frame, then the 100 ms encode leaves for the ACK";
  ASSERT_EQ(b.size(), a.size());
  std::vector<float> spliced(a.begin(), a.begin() + kChord);
  spliced.insert(spliced.end(), b.begin() + kChord, b.end());
  dtmf::physical::write_wav_file(path("c.wav"), spliced, 48000);
  const Result dec = run("decode --profile fast --json " + path("c.wav"));
  ASSERT_EQ(dec.exit_code, 0) << dec.out;
  const auto heard = json_lines(dec.out);
  ASSERT_EQ(heard.size(), 1u) << dec.out;
  EXPECT_FALSE(heard[0]["crc_ok"].get<bool>()) << dec.out;
  // The clean frame, cut the same way, is heard intact and once.
  const Result clean = run("decode --profile fast --json " + path("a.wav"));
  const auto intact = json_lines(clean.out);
  ASSERT_EQ(intact.size(), 1u) << clean.out;
  EXPECT_TRUE(intact[0]["crc_ok"].get<bool>());
}

TEST_F(Dtmfctl, SimulatedDistanceAndNoiseStillDecode) {
  ASSERT_EQ(run("encode --wav " + path("t.wav") + " turn --rotation -30").exit_code, 0);
  const Result sim = run("simulate " + path("t.wav") + " " + path("h.wav") +
                         " --distance 7 --noise pink --noise-dbfs -45 --reverb-rt60 0.4 --clock-ppm 80");
  ASSERT_EQ(sim.exit_code, 0) << sim.out;
  const Result dec = run("decode " + path("h.wav"));
  ASSERT_EQ(dec.exit_code, 0) << dec.out;
  EXPECT_NE(dec.out.find("command turn rotation=-30."), std::string::npos) << dec.out;
  EXPECT_NE(dec.out.find("3 frames heard, 3 intact"), std::string::npos) << dec.out;
}

TEST_F(Dtmfctl, HumanOutputNamesEveryFrameAndWhatItEncodes) {
  const Result r = run("encode stop");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("frame 1/2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frame 2/2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("encodes: stop"), std::string::npos) << r.out;
}

TEST_F(Dtmfctl, OutOfRangeValuesAreUsageErrorsNamingTheField) {
  Result r = run("encode drive --speed 120");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("speed_percent 120 is out of range: allowed 0..100"), std::string::npos) << r.out;
  r = run("encode turn --rotation 10 --duration 9");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("duration_s"), std::string::npos) << r.out;
  r = run("encode --word 4096");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  r = run("encode drive");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--speed"), std::string::npos) << r.out;
  r = run("encode");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  r = run("encode --word 5 stop");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  r = run("encode --profile nosuch reset");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("seed"), std::string::npos) << r.out;
}

TEST_F(Dtmfctl, UnreadableRecordingsFailWithTheFileNamed) {
  std::FILE* f = std::fopen(path("notes.txt").c_str(), "w");
  std::fputs("not audio\n", f);
  std::fclose(f);
  Result r = run("decode " + path("notes.txt"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find(path("notes.txt")), std::string::npos) << r.out;
  r = run("decode " + path("absent.wav"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("absent.wav"), std::string::npos) << r.out;
}

TEST_F(Dtmfctl, HelpListsSubcommandsAndExitCodes) {
  const Result r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* word : {"encode", "decode", "simulate", "Exit codes"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  }
  // The connection and output flags are the top level's, listed once.
  for (const std::string flag : {"--server", "--tls-ca", "--token-file", "--json"}) {
    int listed = 0;  // option lines: "  --flag ..."
    for (std::size_t at = r.out.find("\n  " + flag); at != std::string::npos; at = r.out.find("\n  " + flag, at + 1))
      ++listed;
    EXPECT_EQ(listed, 1) << flag << "\n" << r.out;
  }
}

TEST_F(Dtmfctl, GlobalFlagsWorkBeforeOrAfterTheSubcommand) {
  // --json anywhere gives the same output.
  const Result before = run("--json encode --word 2861"), after = run("encode --word 2861 --json");
  ASSERT_EQ(before.exit_code, 0) << before.out;
  EXPECT_EQ(before.out, after.out);
  EXPECT_EQ(json_lines(before.out).size(), 1u);
  const Result nested = run("encode drive --speed 10 --json");
  EXPECT_EQ(json_lines(nested.out).size(), 3u) << nested.out;
  // --server before the subcommand is no usage error: it tries that server (nothing there: 4).
  for (const std::string args : {"--server 127.0.0.1:1 health", "--token-file /dev/null stop --server=127.0.0.1:1"}) {
    const Result r = run(args + " < /dev/null");
    EXPECT_EQ(r.exit_code, 4) << args << ": " << r.out;
    EXPECT_NE(r.out.find("cannot reach dtmf-server at 127.0.0.1:1"), std::string::npos) << args << ": " << r.out;
  }
  // A flag nobody knows is still a usage error, wherever it stands.
  EXPECT_EQ(run("--bogus health").exit_code, 2);
  EXPECT_EQ(run("health --bogus").exit_code, 2);
  EXPECT_EQ(run("report --csv --json --server 127.0.0.1:1").exit_code, 2);
}

// Keys offline: keygen writes a key only its owner may read; encode --key renders
// authenticated frames numbered from its own counters (a second run continues past the
// first, never reusing one); decode --key says of each frame whether its MAC holds, and
// under another key refuses them all; a key file others may read is refused with the fix.
TEST_F(Dtmfctl, KeysMakeAuthenticatedFramesThatOnlyTheSameKeyAccepts) {
  const Result made = run("keygen " + path("a.key"));
  ASSERT_EQ(made.exit_code, 0) << made.out;
  ASSERT_EQ(run("keygen " + path("b.key")).exit_code, 0);
  EXPECT_EQ(fs::status(path("a.key")).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_NE(run("keygen " + path("a.key")).exit_code, 0) << "never overwrites a key";

  const std::string keyed = "--key " + path("a.key") + " --state-dir " + path("state") + " --profile fast --json ";
  const Result first = run("encode " + keyed + "--wav " + path("f.wav") + " drive --speed 40");
  ASSERT_EQ(first.exit_code, 0) << first.out;
  const auto sent = json_lines(first.out);
  ASSERT_EQ(sent.size(), 2u) << "a counter synchronisation, then the command";
  EXPECT_TRUE(sent[0]["synchronisation"].get<bool>());
  EXPECT_EQ(sent[1]["frame"].get<std::string>().size(), 80u);
  EXPECT_EQ(sent[1]["tones_hz"].size(), 24u) << "three chords of eight tones";
  // With a key and no --profile: authenticated (fast), never the seed's frames without a MAC.
  const Result second = run("encode --key " + path("a.key") + " --state-dir " + path("state") + " --json stop");
  ASSERT_EQ(second.exit_code, 0) << second.out;
  const auto later = json_lines(second.out);
  ASSERT_FALSE(later.empty());
  EXPECT_GT(later.front()["counter"].get<std::uint64_t>(), sent[1]["counter"].get<std::uint64_t>());
  for (const auto& frame : later) EXPECT_TRUE(frame["authenticated"].get<bool>()) << second.out;

  const Result good = run("decode --key " + path("a.key") + " --profile fast --json " + path("f.wav"));
  ASSERT_EQ(good.exit_code, 0) << good.out;
  const auto heard = json_lines(good.out);
  ASSERT_EQ(heard.size(), 2u) << good.out;
  EXPECT_TRUE(heard[1]["authenticated"].get<bool>());
  EXPECT_EQ(heard[1]["event"]["kind"], "command");
  EXPECT_EQ(heard[1]["frame"], sent[1]["frame"]);

  const Result other = run("decode --key " + path("b.key") + " --profile fast " + path("f.wav"));
  EXPECT_NE(other.out.find("REFUSED (authentication)"), std::string::npos) << other.out;
  EXPECT_NE(other.out.find("0 MACs held, 2 frames refused for authentication"), std::string::npos) << other.out;

  fs::permissions(path("b.key"), fs::perms::group_read, fs::perm_options::add);
  const Result open = run("encode --key " + path("b.key") + " --profile fast stop");
  EXPECT_EQ(open.exit_code, 1);
  EXPECT_NE(open.out.find("chmod 600"), std::string::npos) << open.out;
  // The secret is in no output.
  std::FILE* f = std::fopen(path("a.key").c_str(), "r");
  ASSERT_NE(f, nullptr);
  char text[512] = {};
  const std::size_t n = std::fread(text, 1, sizeof text - 1, f);
  std::fclose(f);
  const std::string file(text, n);
  const auto at = file.find("\nkey ");
  ASSERT_NE(at, std::string::npos);
  const std::string secret = file.substr(at + 5, 64);
  for (const Result* r : {&made, &first, &second, &good, &other}) EXPECT_EQ(r->out.find(secret), std::string::npos);
}

TEST_F(Dtmfctl, AVelocityFrameEncodesOfflineAndDecodesBackAsTheSameVelocity) {
  const Result enc = run("encode --profile fast --json --wav " + path("v.wav") +
                         " velocity --linear-mps -0.05 --angular-radps 0.4 --lease-s 0.5");
  ASSERT_EQ(enc.exit_code, 0) << enc.out;
  const auto sent = json_lines(enc.out);
  ASSERT_EQ(sent.size(), 1u) << enc.out;
  const std::string what = sent[0]["command"].get<std::string>();
  // -0.05 / 0.22 and 0.4 / 2.84 of a Burger's limits, at the payload's resolution (1/2047, 1/127, and
  // the lease in steps of 0.125 s: 0.5 s exactly).
  EXPECT_EQ(what, "velocity linear=-22.7% angular=+14.2% lease=0.50s") << what;
  const Result dec = run("decode --profile fast --json " + path("v.wav"));
  ASSERT_EQ(dec.exit_code, 0) << dec.out;
  const auto heard = json_lines(dec.out);
  ASSERT_EQ(heard.size(), 1u) << dec.out;
  EXPECT_EQ(heard[0]["what"], what);

  Result r = run("encode --profile seed velocity --linear-mps 0.1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("seed profile's 12-bit words cannot carry it"), std::string::npos) << r.out;
  r = run("encode --profile fast velocity --linear-mps 0.3");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("linear_mps 0.3 is out of range for a burger: allowed -0.22..0.22 m/s"), std::string::npos)
      << r.out;
  r = run("encode --profile fast velocity --linear-mps 0.25 --robot waffle");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  r = run("encode --profile fast velocity --angular-radps 1 --lease-s 3");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("lease_s 3 is out of range: allowed 0.3..2"), std::string::npos) << r.out;
}

TEST_F(Dtmfctl, TeleopWithoutATerminalRefusesWithAClearMessage) {
  const Result r = run("teleop < /dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("teleop needs a terminal"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Client.teleop()"), std::string::npos) << r.out;
}

// FFTW's wisdom (signal/fft_wisdom.h): the first decode measures its plans and saves them;
// a later one finds them there and has nothing new to save; a file that is garbage or a
// place that cannot be written costs time only, never the result.
TEST_F(Dtmfctl, DecodeSavesItsFftPlansOnceAndSurvivesABadWisdomFile) {
  ASSERT_EQ(run("encode --profile fast --json --wav " + path("f.wav") + " drive --speed 40").exit_code, 0);
  const std::string wisdom = path("cache/fftw-wisdom");
  const auto decode = [&](const std::string& file) {
    return dtmf::test_support::run_command("env DTMF_FFTW_WISDOM=" + file + " " + DTMFCTL_PATH +
                                           " decode --json --profile fast " + path("f.wav"))
        .out;
  };
  const std::string heard = decode("none");
  ASSERT_EQ(json_lines(heard).size(), 1u) << heard;
  EXPECT_FALSE(fs::exists(wisdom));

  EXPECT_EQ(decode(wisdom), heard);
  ASSERT_TRUE(fs::exists(wisdom));  // the directory made, the plans saved
  std::string text(fs::file_size(wisdom), '\0');
  std::FILE* f = std::fopen(wisdom.c_str(), "r");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(std::fread(text.data(), 1, text.size(), f), text.size());
  std::fclose(f);
  EXPECT_NE(text.find("fftwf_wisdom"), std::string::npos) << text;
  const auto saved_at = fs::last_write_time(wisdom);
  EXPECT_EQ(decode(wisdom), heard);
  EXPECT_EQ(fs::last_write_time(wisdom), saved_at);  // nothing measured, nothing saved

  std::FILE* garbage = std::fopen(wisdom.c_str(), "w");
  std::fputs("(not wisdom at all", garbage);
  std::fclose(garbage);
  EXPECT_EQ(decode(wisdom), heard);
  EXPECT_EQ(decode("/proc/no-such-place/fftw-wisdom"), heard);
}
