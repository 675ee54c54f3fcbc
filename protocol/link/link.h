// One interface for what a link profile does, whatever its wire format: the sender's path
// (command -> frames -> audio), the robot's path (audio -> verdicts on frames -> commands)
// with its answer (ACK / NACK audio), and the sender's ear (audio -> answers).
//
// Programs and benchmarks make a link with make_link(profile, options) and use only this:
// none of them asks which wire format a profile has. The options carry what a link needs
// beyond its profile: the key it shares with its peer, where its freshness counters live,
// and the robot's address. Each format keeps its own paths behind it (the seed's words:
// seed_link.cpp with seed_sender_path.h and seed_receiver_path.h; the fast profile's frames:
// fast_link.cpp with hop_frame_path.h), so adding or changing a profile touches protocol/
// and the docs only. A link numbers the frames it plans (sequence numbers, or with a key its
// freshness counter) and the robot's side remembers what it accepted: a link is one sender's
// or one robot's, used from one thread at a time. No device, no clock of its own: audio is
// rendered, and the robot's wall clock, which counters are checked against, is given.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "command/command.h"
#include "link/reception.h"
#include "link/renewal_planner.h"
#include "link/transmit_plan.h"
#include "profile/link_profile.h"
#include "security/counter_store.h"
#include "security/link_key.h"

namespace dtmf::link {

struct LinkOptions {
  // The key the sender and its robots share. With one, every frame that can carry a MAC
  // does (the fast profile's), and the robot executes only frames whose MAC holds and whose
  // counter is new; without one, frames go unauthenticated and authenticated ones are
  // refused, since there is nothing to check them with.
  std::shared_ptr<const security::LinkKey> key;
  // The freshness counters (the sender's next, the robot's last accepted): on disk for a
  // program (security/counter_file.h); none given with a key, one in memory for this link.
  std::shared_ptr<security::CounterStore> counters;
  std::uint8_t address = 0;  // the robot's address (0..7): a robot takes frames sent to it
  // The robot's: the room key, which every robot and sender of a room holds for the stop every
  // robot obeys (docs/security.md, "The room key"), and the newest room counter taken
  // (security/room_freshness.h). With it, a stop for every robot is taken only under it. A
  // sender sends that stop on a link of its own whose `key` is the room key.
  std::shared_ptr<const security::LinkKey> room_key;
  std::shared_ptr<security::CounterStore> room_counters;
  // The robot's clock (security/counter_clock.h): counters name times, and a frame whose
  // counter lies more than kClockMarginS ahead of this clock is never taken nor kept (a Stop
  // still stops). Given, as the audio is, so that tests can set it a day off.
  std::function<std::chrono::system_clock::time_point()> wall_clock = std::chrono::system_clock::now;
  // A robot with a key that executes unauthenticated frames too (the seed profile's, which
  // cannot carry a MAC): the exception `dtmf-agent --accept-unauthenticated` makes.
  bool accept_unauthenticated = false;
  // The sender's first sequence number for unauthenticated numbered frames; none: random,
  // so that a robot that executed frame n of a sender's former run does not take this run's
  // first frame for a retransmission of it.
  std::optional<std::uint8_t> first_sequence;
};

// The robot's receive path: audio in, verdicts out. Times are milliseconds since the first
// sample fed. The returned span is valid until the next call.
class FrameReceiver {
 public:
  virtual ~FrameReceiver() = default;
  virtual std::span<const Reception> feed(std::span<const float> samples) = 0;
  // Frames read again out of the room's echo of a frame taken lately, and ignored
  // (reliability/echo_memory.h); formats that keep no such memory say 0.
  virtual std::size_t echoes_ignored() const { return 0; }
};

// The reception of `frame` taken intact and executed, as the robot's receiver would give it:
// what benchmarks and tests answer when they play the robot without its receiver.
inline Reception intact_reception(const TransmitFrame& frame) {
  Reception r;
  r.bits = frame.bits;
  r.bit_count = frame.bit_count;
  r.intact = true;
  r.event = ReceptionEvent::Command;
  r.authenticated = frame.authenticated;
  r.sequence = frame.sequence;
  r.counter = frame.counter;
  r.heard_ms = frame.tone_ms;  // decided as the frame ends (start_ms 0): the answer may follow at once
  return r;
}

// The sender's ear: audio in, answers out.
class AnswerListener {
 public:
  virtual ~AnswerListener() = default;
  virtual std::span<const Answer> feed(std::span<const float> samples) = 0;
};

class Link {
 public:
  Link(const LinkProfile& profile, LinkOptions options);
  virtual ~Link() = default;
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  const LinkProfile& profile() const { return profile_; }
  const std::string& name() const { return profile_.name; }
  const LinkOptions& options() const { return options_; }
  // Whether this link has a key (its frames are authenticated where the format allows).
  bool keyed() const { return options_.key != nullptr; }
  // Whether its format carries a MAC at all (the seed's 16-bit frames cannot).
  virtual bool can_authenticate() const = 0;
  // Whether its frames name the robot they are for (the seed's 16-bit frames do not: every
  // robot in the room that hears one executes it).
  virtual bool addresses_robots() const = 0;

  // --- the sender ---
  // The frames of `command` in transmission order, with their audio, each numbered anew (a
  // sequence number, or a freshness counter that is never used again). With a key, a
  // counter synchronisation frame goes first when the robot may not be able to complete the
  // counter (security/freshness.h). Throws command::ParameterError for a bad parameter.
  virtual std::vector<TransmitFrame> plan(const command::Command& command) = 0;
  // How many frames `command` takes (a synchronisation frame not counted); throws
  // command::ParameterError for a command the format cannot carry, as plan() would.
  virtual std::size_t frame_count(const command::Command& command) const = 0;
  // One frame carrying a raw payload word (Reception::payload_word), for formats whose
  // payload is one (dtmfctl encode --word); nothing for formats that only send whole commands.
  virtual std::optional<TransmitFrame> plan_payload_word(std::uint32_t word) const;
  // `command` as the robot will execute it: its parameters through the format's fields.
  virtual command::Command as_received(const command::Command& command) const = 0;
  // Payload bits a command's frames carry, the check and the MAC excluded (throughput).
  virtual int payload_bits(const command::Command& command) const = 0;
  // A frame of random content that a sender could send (seeded), for benchmarks: every
  // value its fields can take, not just the commands of a test sequence. Numbered like plan():
  // the next sequence number or counter, so that no frame repeats one of the last 15.
  virtual TransmitFrame random_frame(std::uint64_t seed) = 0;
  // Offline (dtmfctl encode --wav): where frame `index` of a recording starts, and the
  // frames laid out so, each followed by the silence a sender leaves for its answer.
  virtual double frame_start_ms(std::size_t index) const = 0;
  std::vector<float> render(std::span<const TransmitFrame> frames) const;
  // The robot confirmed `frame` (an answer for which answers() held): with a key, the
  // counter it confirmed is on record.
  virtual void confirmed(const TransmitFrame& frame);
  // One frame, unanswered, that renews the lease of the velocity each of `robots` (one link
  // per robot) was sent last, and which of them it renews: at most three, in order. Planned by
  // plan_joint_renewal (renewal_planner.h), to which this gives the robots' records and fresh
  // counters and whose numbers it records in their links and stores. Left out are links of
  // another profile than this one's or whose format has no such frame (renews_jointly()),
  // robots whose last frame was no velocity and, keyed, robots that could not complete the
  // renewal's counter from that frame's (their next frame is in step). Nothing when none can
  // be renewed. Throws MixedRenewal for keyed and plain robots together, and what a counter
  // store throws.
  struct PlannedRenewal {
    TransmitFrame frame;
    std::vector<std::size_t> renewed;  // indices into `robots`
  };
  std::optional<PlannedRenewal> plan_renewal(std::span<Link* const> robots);
  virtual bool renews_jointly() const { return false; }
  // What this link's sender keeps for its robot's joint renewals (renewal_planner.h); none
  // where the format renews no lease jointly.
  virtual RenewalRecord* renewal_record() { return nullptr; }

  // --- the robot ---
  virtual std::unique_ptr<FrameReceiver> receiver() const = 0;
  // The answer to `reception`: ACK (naming the frame, or with a key bound to it by a tag)
  // for an intact frame it accepted, NACK for any other; no audio for one it leaves
  // unanswered (Reception::answered).
  virtual std::vector<float> answer_audio(const Reception& reception) const = 0;
  // The block a live receiver should be fed in (its analysis hop).
  virtual int receiver_block_samples() const = 0;

  // --- the sender's ear ---
  virtual std::unique_ptr<AnswerListener> answer_listener() const = 0;
  // The block to read the microphone in, so an answer is heard as soon as it is complete.
  virtual int answer_block_samples() const = 0;
  // Whether `answer` answers `frame`: a named ACK must name it, a tagged one carry its tag.
  virtual bool answers(const Answer& answer, const TransmitFrame& frame) const = 0;

 protected:
  const LinkProfile& profile_;
  LinkOptions options_;
};

// The link of `profile` with `options`: what every program, benchmark and test uses.
std::unique_ptr<Link> make_link(const LinkProfile& profile, LinkOptions options = {});
// One link per profile in all_profiles() (or those given), with the same options.
std::vector<std::unique_ptr<Link>> make_links(const LinkOptions& options,
                                              const std::vector<const LinkProfile*>& profiles = all_profiles());
// The file the FFT plans of every link's receivers and ears are kept in, so that a machine
// measures each size once (signal/fft_wisdom.h: $DTMF_FFTW_WISDOM, then the cache
// directories; "" for none). Programs call use_plan_cache(plan_cache_default_file()) once,
// before they build a receiver.
std::string plan_cache_default_file();
void use_plan_cache(const std::string& path);
// A sender's profile when none is named: with a key the first of `links` that authenticates
// its frames (fast), else the first (seed). Nothing goes out without a MAC by default.
const LinkProfile& default_profile(std::span<const std::unique_ptr<Link>> links);

}  // namespace dtmf::link
