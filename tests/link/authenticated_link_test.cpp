// The fast profile's authenticated frames against an attacker with a loudspeaker: a recorded
// session replayed (before and after the robot restarts), a frame captured and played after
// a newer one (RollJam), a wrong key, a million random frames, every one- and two-symbol
// change of valid frames, a retransmission after a lost ACK, and a sender that lost its state.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <random>

#include "command/command.h"
#include "command/command_payload.h"
#include "link/frame_admission.h"
#include "link/link.h"
#include "reliability/sealed_frame.h"
#include "security/counter_file.h"
#include "security/frame_mac.h"
#include "security/freshness.h"
#include "signal/hop_synthesizer.h"
#include "support/temp_dir.h"

using namespace dtmf;
namespace fs = std::filesystem;

namespace {

const LinkProfile& p = fast_profile();

std::shared_ptr<const security::LinkKey> fixed_key(unsigned char fill) {
  std::array<unsigned char, security::kKeyBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(fill + 7 * i);
  return security::LinkKey::from_bytes(bytes);
}

link::LinkOptions keyed(std::shared_ptr<const security::LinkKey> key,
                        std::shared_ptr<security::CounterStore> counters = nullptr) {
  link::LinkOptions o;
  o.key = std::move(key);
  o.counters = counters ? std::move(counters) : std::make_shared<security::MemoryCounterStore>();
  return o;
}

struct Heard {
  int executed = 0, repeats = 0, refused_for_authentication = 0, synchronised = 0, broken = 0;
  std::vector<std::string> commands;
};

// `audio` through a robot's receiver.
Heard hear(link::FrameReceiver& receiver, const std::vector<float>& audio) {
  Heard h;
  for (std::size_t at = 0; at < audio.size(); at += 1024) {
    for (const auto& r :
         receiver.feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(1024, audio.size() - at)))) {
      if (r.command) {
        ++h.executed;
        h.commands.push_back(command::describe(*r.command));
      }
      h.repeats += r.event == link::ReceptionEvent::Repeat;
      h.synchronised += r.event == link::ReceptionEvent::Synchronised;
      h.broken += !r.intact;
      h.refused_for_authentication += r.refusal == link::RefusalReason::Authentication;
    }
  }
  return h;
}

std::vector<float> with_silence_after(std::vector<float> audio) {
  audio.resize(audio.size() + 48000, 0.0f);
  return audio;
}

// A session as the sender plays it and an attacker records it: each frame confirmed.
std::vector<link::TransmitFrame> session(link::Link& sender, const std::vector<command::Command>& commands) {
  std::vector<link::TransmitFrame> frames;
  for (const auto& c : commands) {
    for (auto& f : sender.plan(c)) {
      sender.confirmed(f);
      frames.push_back(std::move(f));
    }
  }
  return frames;
}

const std::vector<command::Command> kSession = {command::DriveForward{60}, command::Turn{-40},
                                                command::DriveForDuration{80, 3}, command::Stop{}};

// A directory of its own under /tmp for each test.
struct TempDir : dtmf::test_support::TempDir {
  TempDir() : dtmf::test_support::TempDir("dtmf-auth") {}
};

}  // namespace

TEST(AuthenticatedLink, ARecordedSessionReplayedExecutesNothingBeforeOrAfterTheRobotRestarts) {
  TempDir dir;
  const auto key = fixed_key(1);
  const auto sender = link::make_link(p, keyed(key));
  const auto recording = with_silence_after(sender->render(session(*sender, kSession)));
  {
    const auto robot =
        link::make_link(p, keyed(key, security::FileCounterStore::open_robot(dir.path, *key, security::RobotKey::New)));
    const auto receiver = robot->receiver();
    const Heard first = hear(*receiver, recording);
    EXPECT_EQ(first.executed, 4);
    EXPECT_EQ(first.synchronised, 1);
    const Heard replay = hear(*receiver, recording);
    EXPECT_EQ(replay.executed, 0) << "the same robot, the session played again";
    // The last frame again is the last frame: answered (its ACK may have been lost), not executed.
    EXPECT_EQ(replay.repeats, 1);
    EXPECT_EQ(replay.refused_for_authentication, 4);
  }
  // The robot restarts: its counter comes back from disk.
  const auto robot = link::make_link(p, keyed(key, security::FileCounterStore::open_robot(dir.path, *key)));
  const Heard after_restart = hear(*robot->receiver(), recording);
  EXPECT_EQ(after_restart.executed, 0) << "after a restart";
  EXPECT_EQ(after_restart.refused_for_authentication, 4);
}

// RollJam: the attacker jams the robot while recording frame A; the sender, unanswered, goes
// on with frame B, which the robot executes; A played then is refused.
TEST(AuthenticatedLink, AFrameCapturedAndPlayedAfterANewerOneIsRefused) {
  const auto key = fixed_key(2);
  const auto sender = link::make_link(p, keyed(key));
  const auto sync_and_a = sender->plan(command::DriveForward{100});
  ASSERT_EQ(sync_and_a.size(), 2u);
  sender->confirmed(sync_and_a[0]);  // the synchronisation got through; A was jammed
  const auto b = sender->plan(command::Stop{});
  ASSERT_EQ(b.size(), 1u);
  const auto robot = link::make_link(p, keyed(key));
  const auto receiver = robot->receiver();
  const Heard first =
      hear(*receiver, with_silence_after(sender->render(std::vector<link::TransmitFrame>{sync_and_a[0], b[0]})));
  EXPECT_EQ(first.commands, std::vector<std::string>{"stop"});
  const Heard replay =
      hear(*receiver, with_silence_after(sender->render(std::vector<link::TransmitFrame>{sync_and_a[1]})));
  EXPECT_EQ(replay.executed, 0);
  EXPECT_EQ(replay.refused_for_authentication, 1);
}

TEST(AuthenticatedLink, AFrameUnderAnotherKeyIsRefusedAndSoIsAnUnauthenticatedOne) {
  const auto sender = link::make_link(p, keyed(fixed_key(3)));
  const auto robot = link::make_link(p, keyed(fixed_key(4)));
  const Heard h = hear(*robot->receiver(), with_silence_after(sender->render(session(*sender, kSession))));
  EXPECT_EQ(h.executed, 0);
  EXPECT_EQ(h.refused_for_authentication, 5) << "the synchronisation and four commands";
  const auto unkeyed = link::make_link(p);
  const Heard plain = hear(*robot->receiver(), with_silence_after(unkeyed->render(session(*unkeyed, kSession))));
  EXPECT_EQ(plain.executed, 0);
  EXPECT_EQ(plain.refused_for_authentication, 4);
  link::LinkOptions lenient = keyed(fixed_key(4));
  lenient.accept_unauthenticated = true;
  const auto lenient_robot = link::make_link(p, lenient);
  EXPECT_EQ(hear(*lenient_robot->receiver(), with_silence_after(unkeyed->render(session(*unkeyed, kSession)))).executed,
            4)
      << "--accept-unauthenticated lets them in";
}

// A frame under another key that reaches the robot damaged: its code corrects it, its CRC
// holds, and its MAC fails. It is a forgery to count (refused, authentication), not a damaged
// frame (a NACK the log would count as noise); until 2026-11 it was counted as damaged.
TEST(AuthenticatedLink, AFrameUnderAnotherKeyThatNeededCorrectionsIsRefusedForAuthentication) {
  const auto sender = link::make_link(p, keyed(fixed_key(3)));
  const auto robot = link::make_link(p, keyed(fixed_key(4)));
  for (const int errors : {0, 1, 2, 3}) {
    std::vector<float> audio;
    const auto frames = session(*sender, kSession);  // a synchronisation first, the first time
    for (const auto& frame : frames) {
      auto symbols = reliability::sealed_frame_symbols(frame.bits);
      // `errors` tones sent wrong, each a clear tone of another symbol: more than a refusal
      // may spend on a frame that only its CRC stands behind when errors > 2.
      for (int e = 0; e < errors; ++e) {
        auto& s = symbols[static_cast<std::size_t>(5 + 7 * e)];
        s = static_cast<std::uint8_t>((s + 11) % 32);
      }
      const auto chords = signal::synthesize_hopped_frame(p, symbols);
      audio.insert(audio.end(), chords.begin(), chords.end());
      audio.resize(audio.size() + static_cast<std::size_t>(p.samples_for_ms(400)), 0.0f);
    }
    const Heard h = hear(*robot->receiver(), with_silence_after(audio));
    EXPECT_EQ(h.executed, 0) << errors << " errors";
    EXPECT_EQ(h.broken, 0) << errors << " errors: counted as damaged";
    EXPECT_EQ(h.refused_for_authentication, static_cast<int>(frames.size())) << errors << " errors";
  }
}

// A retransmission after a lost ACK: answered with the frame's tag, not executed again.
TEST(AuthenticatedLink, ARetransmissionIsAnsweredWithItsTagButNotExecutedAgain) {
  const auto key = fixed_key(5);
  const auto sender = link::make_link(p, keyed(key));
  const auto frames = sender->plan(command::DriveForward{30});
  ASSERT_EQ(frames.size(), 2u);
  const auto robot = link::make_link(p, keyed(key));
  const auto receiver = robot->receiver();
  std::vector<link::Reception> got;
  // The retransmission comes after the ACK timeout (500 ms), as a sender's does.
  std::vector<float> audio = sender->render(std::vector<link::TransmitFrame>{frames[0], frames[1]});
  audio.resize(audio.size() + 24000, 0.0f);
  audio.insert(audio.end(), frames[1].audio.begin(), frames[1].audio.end());
  audio = with_silence_after(audio);
  for (std::size_t at = 0; at < audio.size(); at += 1024) {
    for (const auto& r :
         receiver->feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(1024, audio.size() - at)))) {
      got.push_back(r);
    }
  }
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[1].event, link::ReceptionEvent::Command);
  EXPECT_EQ(got[2].event, link::ReceptionEvent::Repeat);
  EXPECT_TRUE(got[2].acknowledged());
  EXPECT_TRUE(got[2].authenticated);
  // Both answers carry the frame's tag.
  for (int i : {1, 2}) {
    const auto ear = sender->answer_listener();
    std::vector<float> answer = robot->answer_audio(got[static_cast<std::size_t>(i)]);
    answer.resize(answer.size() + 4800, 0.0f);
    bool confirmed = false;
    for (const auto& a : ear->feed(answer)) confirmed = confirmed || (a.ack && sender->answers(a, frames[1]));
    EXPECT_TRUE(confirmed) << "answer " << i;
  }
}

// A million random 80-bit frames (their CRC made to hold) and every one- and two-symbol change
// of valid frames: the robot takes none of them. The key is fixed, so the outcome is too.
TEST(AuthenticatedLink, AMillionRandomFramesAndEveryOneAndTwoSymbolChangeAreRefused) {
  const auto key = fixed_key(6);
  link::FrameAdmission robot(p, keyed(key, std::make_shared<security::MemoryCounterStore>(1, 1000)));
  std::mt19937_64 rng(42);
  int taken = 0;
  for (int i = 0; i < 1000000; ++i) {
    reliability::SealedFrame f;
    f.form = rng() % 8 == 0 ? reliability::SealedForm::Sync : reliability::SealedForm::Command;
    f.counter = rng();
    f.payload = static_cast<std::uint32_t>(rng());
    f.mac = static_cast<std::uint32_t>(rng());
    taken += robot.authentic(reliability::sealed_frame_pack(f)) ? 1 : 0;
  }
  EXPECT_EQ(taken, 0);

  // Valid frames the sender made, each symbol of their data changed to every other value,
  // and every pair of symbols: an attacker editing a heard frame.
  const auto sender = link::make_link(p, keyed(key, std::make_shared<security::MemoryCounterStore>(1001)));
  int changed = 0, intact = 0;
  for (const auto& command : {command::Command{command::Stop{}}, command::Command{command::DriveForward{55}}}) {
    const link::TransmitFrame frame = sender->plan(command).back();
    ASSERT_TRUE(robot.authentic(frame.bits)) << "the frame itself is taken";
    const auto word = reliability::sealed_frame_symbols(frame.bits);
    std::array<std::uint8_t, reliability::kSealedDataSymbols> data{};
    std::copy_n(word.begin(), data.size(), data.begin());
    const auto check = [&](const std::array<std::uint8_t, reliability::kSealedDataSymbols>& d) {
      const auto bits = reliability::sealed_frame_data_bits(d);
      ++changed;
      if (!reliability::sealed_frame_unpack(bits)) return;  // its CRC fails: a damaged frame, NACKed
      ++intact;
      taken += robot.authentic(bits) ? 1 : 0;
    };
    for (std::size_t i = 0; i < data.size(); ++i) {
      for (std::uint8_t v = 0; v < 32; ++v) {
        if (v == data[i]) continue;
        auto d = data;
        d[i] = v;
        check(d);
        for (std::size_t j = i + 1; j < data.size(); ++j) {
          for (std::uint8_t w = 0; w < 32; ++w) {
            if (w == data[j]) continue;
            auto dd = d;
            dd[j] = w;
            check(dd);
          }
        }
      }
    }
  }
  EXPECT_EQ(taken, 0);
  EXPECT_EQ(changed, 2 * (16 * 31 + 120 * 31 * 31));
  std::printf("%d changed frames, %d of them with a CRC that holds, none taken\n", changed, intact);
}

// The sender loses its state (a new machine, the same key): its counter starts from the
// clock, its first command synchronises, and the robot takes it; what the old sender sent
// stays refused.
TEST(AuthenticatedLink, ASenderThatLostItsStateRecoversAndNothingOldBecomesReplayable) {
  TempDir dir;
  const auto key = fixed_key(7);
  const auto t0 = std::chrono::system_clock::now();
  const auto old_sender = link::make_link(
      p, keyed(key, security::FileCounterStore::open_sender(dir.path / "old", *key, [&] { return t0; })));
  const auto robot = link::make_link(p, keyed(key));
  const auto receiver = robot->receiver();
  const auto old_session = with_silence_after(old_sender->render(session(*old_sender, kSession)));
  EXPECT_EQ(hear(*receiver, old_session).executed, 4);

  // Ten seconds later, a new machine with the same key and an empty state directory.
  const auto new_sender =
      link::make_link(p, keyed(key, security::FileCounterStore::open_sender(
                                        dir.path / "new", *key, [&] { return t0 + std::chrono::seconds(10); })));
  const auto fresh = new_sender->plan(command::Turn{20});
  ASSERT_EQ(fresh.size(), 2u) << "a synchronisation first";
  EXPECT_TRUE(fresh[0].synchronisation);
  const Heard recovered = hear(*receiver, with_silence_after(new_sender->render(fresh)));
  EXPECT_EQ(recovered.synchronised, 1);
  EXPECT_EQ(recovered.commands,
            std::vector<std::string>{command::describe(command::quantised_payload(command::Turn{20}))});
  const Heard replay = hear(*receiver, old_session);
  EXPECT_EQ(replay.executed, 0);
  EXPECT_EQ(replay.refused_for_authentication, 5);
}
