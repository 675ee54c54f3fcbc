// Signal layer: once running, the listeners allocate nothing per analysis window (the
// receive path must keep up on a Raspberry Pi, where a heap call per 50 ms
// window is a real cost and a source of jitter). Its own executable: it replaces the
// global operator new to count every allocation the process makes.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>

#include "command/test_sequence.h"
#include "link/frame_admission.h"
#include "link/hop_frame_path.h"
#include "link/link.h"
#include "link/seed_sender_path.h"
#include "profile/link_profile.h"
#include "reliability/reply_code.h"
#include "signal/hop_listener.h"
#include "signal/hop_reply.h"
#include "signal/hop_synthesizer.h"
#include "signal/synthesizer.h"
#include "signal/tone_listener.h"
#include "sim/noise.h"
#include "support/seed_audio.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// The replacements pair malloc with free on purpose; GCC cannot see that they are the pair.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace dtmf;

namespace {

// The seed's 65 frames back to back, in pink noise at -40 dBFS.
std::vector<float> busy_audio(const LinkProfile& profile) {
  std::vector<link::SeedPlannedFrame> frames;
  for (const auto& command : command::seed_test_sequence()) {
    for (const auto& f : link::plan_command(profile, command)) frames.push_back(f);
  }
  std::vector<float> audio = test_support::seed_audio(profile, frames);
  sim::NoiseSource noise(sim::parse_noise("pink", -40), profile.sample_rate_hz, 7);
  noise.add_to(audio);
  return audio;
}

long allocations_while_feeding(signal::ToneListener& listener, std::span<const float> audio, std::size_t block,
                               std::size_t& heard) {
  heard = 0;
  const long before = g_allocations.load();
  for (std::size_t at = 0; at < audio.size(); at += block) {
    heard += listener.feed(audio.subspan(at, std::min(block, audio.size() - at))).size();
  }
  return g_allocations.load() - before;
}

}  // namespace

TEST(ListenerAllocation, TheCountingAllocatorSeesAllocations) {
  const long before = g_allocations.load();
  auto* v = new std::vector<int>(100);
  delete v;
  EXPECT_GE(g_allocations.load() - before, 2);
}

TEST(ListenerAllocation, TheRobotsListenerAllocatesNothingWhileHearingTheSeedSequence) {
  const LinkProfile& profile = seed_profile();
  const auto audio = busy_audio(profile);
  for (std::size_t block : {std::size_t{480}, std::size_t{2400}, std::size_t{4096}}) {
    auto listener = signal::chord_listener(profile);
    std::size_t heard = 0;
    EXPECT_EQ(allocations_while_feeding(listener, audio, block, heard), 0) << "block " << block;
    EXPECT_EQ(heard, 65u) << "block " << block;  // and it did hear every frame
  }
}

TEST(ListenerAllocation, TheSendersListenerAllocatesNothingWhileHearingAnswers) {
  const LinkProfile& profile = seed_profile();
  // 20 answers, ACK and NACK in turn, each followed by a second of silence.
  std::vector<float> audio;
  for (int i = 0; i < 20; ++i) {
    const auto reply = signal::synthesize_reply(profile, i % 2 ? signal::Reply::Nack : signal::Reply::Ack);
    audio.insert(audio.end(), reply.begin(), reply.end());
    audio.resize(audio.size() + static_cast<std::size_t>(profile.sample_rate_hz), 0.0f);
  }
  auto listener = signal::reply_listener(profile);
  std::size_t heard = 0;
  EXPECT_EQ(allocations_while_feeding(listener, audio, 480, heard), 0);
  EXPECT_EQ(heard, 20u);
}

// The fast profile's robot path (listener, Reed-Solomon, gate, MAC check) and the sender's
// reply listener: the seed sequence's 27 commands as fast frames, unauthenticated and then
// authenticated (with the synchronisation before them), then 17 named replies.
TEST(ListenerAllocation, TheFastProfilesListenersAllocateNothingWhileHearingFramesAndReplies) {
  const LinkProfile& profile = fast_profile();
  link::LinkOptions keyed;
  keyed.key = security::LinkKey::generate();
  const auto plain = link::make_link(profile);
  const auto sealed = link::make_link(profile, keyed);
  link::LinkOptions robot_options = keyed;
  robot_options.counters = std::make_shared<security::MemoryCounterStore>();
  link::FrameAdmission robot(profile, robot_options);
  std::vector<float> audio;
  std::size_t sent = 0;
  for (link::Link* l : {plain.get(), sealed.get()}) {
    for (const auto& command : command::seed_test_sequence()) {
      for (const auto& f : l->plan(command)) {
        l->confirmed(f);
        audio.insert(audio.end(), f.audio.begin(), f.audio.end());
        audio.resize(audio.size() + 4800, 0.0f);  // the ACK's time
        ++sent;
      }
    }
  }
  sim::NoiseSource noise(sim::parse_noise("pink", -40), profile.sample_rate_hz, 7);
  noise.add_to(audio);
  std::vector<float> replies;
  for (int s = 0; s <= 16; ++s) {
    const auto r = signal::synthesize_hopped_reply(
        profile, reliability::reply_codeword({s < 16, static_cast<std::uint8_t>(s % 16)}), s % 2);
    replies.insert(replies.end(), r.begin(), r.end());
    replies.resize(replies.size() + 2400, 0.0f);
  }
  for (std::size_t block : {std::size_t{480}, std::size_t{2400}, std::size_t{4096}}) {
    link::HopFramePath path(profile, [&](const reliability::FrameBits& bits) { return robot.authentic(bits); });
    signal::HopReplyListener reply_listener(profile, profile.hops().reply_tones_needed);
    std::size_t frames = 0, answers = 0;
    const long before = g_allocations.load();
    for (std::size_t at = 0; at < audio.size(); at += block) {
      frames += path.feed(std::span<const float>(audio).subspan(at, std::min(block, audio.size() - at))).size();
    }
    for (std::size_t at = 0; at < replies.size(); at += block) {
      answers +=
          reply_listener.feed(std::span<const float>(replies).subspan(at, std::min(block, replies.size() - at))).size();
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << "block " << block;
    EXPECT_EQ(frames, sent) << "block " << block;
    EXPECT_GE(answers, 17u) << "block " << block;  // a reply's readings: one per window that hears it
  }
}

// Frames at -12 dB SNR: most windows around them fail, and are read again over whole chords
// (signal/whole_chord_reader.h) from the listener's history, in its own buffers.
TEST(ListenerAllocation, WholeChordRereadsAllocateNothing) {
  const LinkProfile& profile = fast_profile();
  link::LinkOptions numbered;  // the same frames in every run
  numbered.first_sequence = 0;
  const auto plain = link::make_link(profile, numbered);
  std::vector<float> audio(9600, 0.0f);
  double power = 0;
  std::size_t frame_samples = 0;
  for (unsigned i = 0; i < 40; ++i) {
    const auto f = plain->random_frame(900 + i);
    for (const float s : f.audio) power += static_cast<double>(s) * s;
    frame_samples += f.audio.size();
    audio.insert(audio.end(), f.audio.begin(), f.audio.end());
    audio.resize(audio.size() + 4800, 0.0f);
  }
  std::mt19937 rng(4);
  std::normal_distribution<float> noise(0.0f,
                                        static_cast<float>(std::sqrt(power / frame_samples * std::pow(10.0, 1.2))));
  for (float& s : audio) s += noise(rng);
  // Takes nothing and asks for every re-read: the listener's whole work on each window.
  struct Count final : signal::CandidateSink {
    std::size_t grid = 0, whole = 0, second = 0;
    bool take(const signal::HopCandidate& c) override {
      ++(c.whole_chords ? whole : c.second_look ? second : grid);
      return false;
    }
    bool none_taken(const signal::HopCandidate&) override { return true; }
  } count;
  signal::HopListener listener(profile);
  const long before = g_allocations.load();
  for (std::size_t at = 0; at < audio.size(); at += 480)
    listener.feed(std::span<const float>(audio).subspan(at, std::min<std::size_t>(480, audio.size() - at)), count);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GE(count.whole, 40u) << "re-reads ran";
  EXPECT_GE(count.second, 40u) << "second looks at the grid's readings ran";
}
