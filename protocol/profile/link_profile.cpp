#include "profile/link_profile.h"
#include "profile/profile_registry.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>

namespace dtmf {

namespace {

LinkProfile make_seed_profile() {
  LinkProfile p;
  WordPlan& w = p.plan.emplace<WordPlan>();
  p.name = "seed";
  p.description = "the seed report's link: 0.8 s four-tone chords, about 17 bit/s";
  // 48 kHz: what the PulseAudio air and most USB microphones run at; 16 kHz tones
  // sit well below its 24 kHz Nyquist limit.
  p.sample_rate_hz = 48000;

  // Seed section 8: bands of 2500 Hz, 0000 = lowest, 1111 = highest tone of the band.
  w.tones.band_low_hz = {4500, 7500, 10500, 13500};
  w.tones.step_hz = 2500.0 / 15.0;
  w.tones.tones_per_band = 16;
  w.tones.ack_hz = {2500, 3500};  // seed section 9
  w.tones.nack_hz = {2000, 3000};
  w.tones.tone_amplitude = 0.2;  // four tones sum to at most 0.8 full scale
  w.tones.edge_ms = 5;           // long enough to keep clicks out of the tone bands

  p.timing.chord_ms = 800;  // seed section 9
  p.timing.gap_ms = 200;
  p.timing.ack_ms = 300;
  p.timing.ack_timeout_ms = 1500;
  p.timing.auto_retransmissions = 1;  // seed section 7, Fig. 8

  w.analysis.fft_size = 4096;  // seed section 8
  w.analysis.analyses_per_s = 20;

  w.robot_detector.bandpass_low_hz = 4000;  // seed section 8
  w.robot_detector.bandpass_high_hz = 17000;
  w.robot_detector.peak_count = 10;
  w.robot_detector.noise_gate_dbfs = -60;
  w.robot_detector.tone_tolerance_hz = 25;
  w.robot_detector.dominance_db = 8;  // spandsp's DTMF relative-peak test
  // Receiver choices of ours (docs/protocol.md §10, "What the seed receiver changed for real
  // rooms"): a moving robot and two sound cards put 16 kHz tones up to 48 Hz off at 3000 ppm,
  // twice the tolerance; a fast profile's sixteen-tone chords must not read as seed chords; a
  // fan's whine on a plan tone must not win its band. A 0.8 s chord lifts its bins'
  // background by 8 dB at most; a whine 50 dB over the floor is learnt in 5 s.
  w.robot_detector.max_offset_ppm = 3000;
  w.robot_detector.crowding_peaks = 3;
  w.robot_detector.background_rise_db_per_s = 10;

  w.sender_detector.bandpass_low_hz = 1500;
  w.sender_detector.bandpass_high_hz = 4000;
  w.sender_detector.peak_count = 5;
  w.sender_detector.noise_gate_dbfs = -60;
  w.sender_detector.tone_tolerance_hz = 25;
  w.sender_detector.dominance_db = 8;
  // ACK tones sit below 3.5 kHz: 3000 ppm moves them 10.5 Hz, within the tolerance.
  w.sender_detector.background_rise_db_per_s = 10;

  w.debounce.min_detections = 2;  // seed section 8
  w.debounce.window_ms = 300;
  // The seed's 0.8 s, plus 0.1 s: a chord passes 0.1-0.15 s after it starts, so 0.8 s let
  // a reverberant tail 8-10 dB down pass it again just after it ended (2 frames in 1000 in
  // the smoking room, RT60 0.76 s). A repeat of the same chord starts 1 s after it.
  w.debounce.lockout_ms = 900;
  w.debounce.rearm_drop_db = 10;  // a reverberant tail must not pass a chord twice
  // A sender starved of the CPU plays a chord with a hole in it (a CI machine: up to 460 ms);
  // the rest, heard after the lockout, passed as a second chord, and the seed's words, having
  // no sequence number, then put the robot's state machine one word off. One chord sounds
  // for at most 0.8 s plus about 0.15 s of window overlap and reverberation; a chord that
  // comes back within 0.6 s of silence must sound 0.3 s more than that before it is new.
  w.debounce.max_dropout_ms = 600;
  w.debounce.presence_margin_ms = 300;
  return p;
}

// The fast profile's answers (docs/protocol.md, "Hearing a frame, answering it").
void plan_fast_replies(HopPlan& h) {
  // Replies: 32 ms windows (31.25 Hz bins), a hop of 4.25 ms, 1 ms fades: a reply chord is
  // 1536 + 2 * 48 + 204 = 1836 samples = 9 hops (38.25 ms), a reply two chords (76.5 ms). In a
  // room a tone of 20 ms smeared into the bins beside it (its early reflections arrive within
  // the window) and was misread, measured through the three rooms, about 10 % of the time; a
  // 32 ms window over a 38 ms chord reads it right.
  h.reply_window_samples = 1536;
  h.reply_hop_samples = 204;
  h.reply_edge_samples = 48;
  h.reply_tones_per_band = HopPlan::kReplyToneValues;
  // Six bands of four tones four bins (125 Hz) apart, lane 0 from 531.25 Hz, lane 1 two bins
  // (62.5 Hz) lower: no tone of a reply lies within three bins of another, whatever the room
  // smears. Answers to consecutive frames alternate lanes, and a Hann window reads nothing of a
  // steady tone two bins away (its zeros lie at whole bins from 2 on), so the last answer's
  // reverberant tail, in a reverberant room as loud as the next answer's direct sound 200 ms
  // later, no longer sits on that answer's bins (docs/protocol.md, "Answers in reverberant
  // rooms"). Every tone lies on an odd bin, so none is 2000, 2500, 3000 or 3500 Hz (bins 64,
  // 80, 96, 112: the seed profile's ACK and NACK tones) and no fast reply sounds like a seed
  // answer. Two lanes two bins apart cannot both keep two bins from every seed tone; this
  // placement leaves one tone of each lane a bin from a seed ACK tone (lane 0 bin 81, lane 1
  // bin 79), so a seed ACK beside the sender costs an answer at most one tone, which a reading
  // may lose (9 of 12 named, 11 of 12 tagged). The top tone, 3406.25 Hz, lies 16 bins of the
  // robot's 25 Hz grid below its lowest band.
  for (int b = 0; b < HopPlan::kReplyBands; ++b) {
    for (int v = 0; v < HopPlan::kReplyToneValues; ++v)
      h.reply_tone_bin[static_cast<std::size_t>(b)][static_cast<std::size_t>(v)] = 17 + 16 * b + 4 * v;
  }
  h.reply_lane_step_bins = -2;
  h.reply_amplitude = 0.8 / HopPlan::kReplyBands;  // the tones of a chord sum to at most 0.8 full scale
  h.reply_presence_db = 3;
  h.reply_onset_db = 3;
  h.reply_background_rise_db_per_s = 10;
  h.reply_tones_needed = 9;  // of 12: named replies differ in at least 7 (reliability/reply_code.h)
  // Tagged ACKs: sixteen tones summing to at most 0.8 full scale, like a frame's eight.
  h.tag_amplitude = h.tone_amplitude / 2;
  h.tag_presence_db = 3;
  h.tag_onset_db = 3;
  // Two chords (102.5 ms): a window wholly inside the frame's last chord lies within it for a
  // robot up to 10 m away ((102.5 - 40 - 2.5) ms of sound there and back).
  h.tag_onset_lookback_hops = 10;
  // Clocks and motion: 750 ppm apart, so no tone is read more than a quarter of a bin (375 ppm
  // at 17.5 kHz) off its bin, from -1875 to +1875 ppm (sound cards' clocks differ by a few
  // hundred; a Burger at full speed adds 640).
  h.tag_offset_ppm = {-1500, -750, 0, 750, 1500};
  // The robot decides about 30 ms before the frame ends; 2 ms covers where it placed the
  // frame's start, 5 ms more how late that may be (the monument chamber's 97.5 % first
  // attempts came from frames begun under the tag chord).
  h.tag_after_frame_ms = 2;
  h.tag_late_ms = 5;
}

// The fast profile, built for real rooms (docs/protocol.md §10 has the reasons and the
// figures): a 40 ms rectangular window on a 25 Hz bin grid, sixteen 32-ary tones per frame
// in two chords of eight on disjoint band sets, Reed-Solomon coded, and one FFT per hop.
LinkProfile make_fast_profile() {
  LinkProfile p;
  p.name = "fast";
  p.description = "a whole command per frame in 102.5 ms, hopped 32-ary tones, Reed-Solomon, named ACKs";
  p.sample_rate_hz = 48000;
  HopPlan& h = p.plan.emplace<HopPlan>();
  h.window_samples = 1920;  // 40 ms; tones 25 Hz apart
  h.edge_samples = 24;      // 0.5 ms fades
  h.hop_samples = 492;      // 10.25 ms; chord = 1920 + 2 * 24 + 492 = 2460 = 5 hops (51.25 ms)
  h.chords_per_frame = 2;
  h.sealed_chords_per_frame = 3;  // 153.75 ms: 24 tones carry an 80-bit authenticated frame
  h.tones_per_band = 32;
  // Sixteen bands of 32 tones and 2 guard bins from 4 kHz: band k starts at bin 160 + 34 k;
  // the first chord sends on the even bands, the second on the odd ones (4.0-17.5 kHz).
  for (int c = 0; c < 2; ++c) {
    for (int b = 0; b < HopPlan::kBandsPerChord; ++b) h.band_first_bin[c][b] = 160 + 34 * (2 * b + c);
  }
  h.tone_amplitude = 0.1;  // eight tones sum to at most 0.8 full scale
  h.gate_db = 7.5;         // noise bands pass 1 in 5, a frame's at -10 dB SNR 24 in 25
  // Of 8: white noise passes both chords 1 window in 610, and a seed chord's four tones cannot
  // fill four bands of both sets at once; 5 of 8 passed 1 in 58 500 but lost 7 % of the
  // frames at -12 dB that the code could decode.
  h.gate_bands = 4;
  h.presence_db = 6;
  h.onset_db = 3;
  h.clear_certainty = 3;  // 4.8 dB: a noise band's best beats its second by this 1 time in 30
  h.background_rise_db_per_s = 10;
  h.max_erasures = 4;         // RS(16, 10) keeps 2 of its 6 parity symbols for detection
  h.sealed_max_erasures = 7;  // RS(24, 16) keeps 1 of its 8
  // A candidate the erasures did not decode gets 2^6 - 1 more tries. At -12 dB (5-of-8 gate)
  // none 75.5 %, 4 tones 84.0 %, 6 tones 85.9 %, 8 tones 86.5 % of 2000 frames (swapped tries
  // then kept 2 parity symbols; they keep 3 now, and with the 4-of-8 gate: 88.7 % of 10 000).
  h.chase_tones = 6;
  h.max_offset_ppm = 3000;
  // A window whose hypotheses all failed, when the next two windows took no frame either (a
  // window a hop early fails where the next decodes: no re-read for those), is read again
  // over 2412 samples of each chord instead of 1920 (signal/whole_chord_reader.h): 1 dB more
  // per tone. Its start is searched in steps of 48 samples (1 ms): at most 24 samples off,
  // 2 % of a tone's power (steps of 24 and 12 heard the same frames). Windows with 3 loud bands
  // in a chord, short of the gate, are re-read too. At -12 dB, 4000 frames: 87.9 % without
  // re-reads, 97.3 % with them, 98.5 % with the 3-band windows as well.
  h.reread_delay_hops = 2;
  h.reread_step_samples = 48;
  h.reread_gate_bands = 3;
  // One verdict per frame: an accept holds its frame's later windows (7 hops); failed
  // candidates less than a chord and a hop apart are one cluster (the first two chords of an
  // authenticated frame fail as a two-chord frame a chord before its own reading), which NACKs
  // no earlier than two chords and three hops after its first candidate.
  h.lockout_hops = 7;
  h.cluster_gap_hops = 5.5;
  h.nack_settle_hops = 13;
  h.repeat_guard_ms = 400;  // a retransmission comes no sooner than the 500 ms ACK timeout
  plan_fast_replies(h);

  // The shared fields, in the units the rest of the code base reads them in.
  const double ms_per_sample = 1000.0 / p.sample_rate_hz;
  p.timing.chord_ms = h.chord_samples() * ms_per_sample;
  p.timing.gap_ms = 0;
  p.timing.ack_ms = h.reply_samples() * ms_per_sample;
  p.timing.ack_timeout_ms = 500;  // an answer comes about 130 ms after the frame starts
  p.timing.auto_retransmissions = 2;
  // Its first attempts were heard in every measured room (docs/benchmarks.md); a second copy
  // stands in for the retransmission a missed ACK would have caused.
  p.timing.broadcast_copies = 2;
  return p;
}

}  // namespace

namespace {
template <class Plan>
Plan& plan_of(const LinkProfile& profile, const std::variant<WordPlan, HopPlan>& plan, const char* what) {
  if (!std::holds_alternative<Plan>(plan))
    throw std::invalid_argument("profile '" + profile.name + "' has no " + what + " (another wire format)");
  return const_cast<Plan&>(std::get<Plan>(plan));
}
}  // namespace

const WordPlan& LinkProfile::words() const { return plan_of<WordPlan>(*this, plan, "word plan"); }
WordPlan& LinkProfile::words() { return plan_of<WordPlan>(*this, plan, "word plan"); }
const HopPlan& LinkProfile::hops() const { return plan_of<HopPlan>(*this, plan, "hopped plan"); }
HopPlan& LinkProfile::hops() { return plan_of<HopPlan>(*this, plan, "hopped plan"); }

int LinkProfile::hop_samples() const {
  if (const auto* w = std::get_if<WordPlan>(&plan))
    return static_cast<int>(std::lround(sample_rate_hz / w->analysis.analyses_per_s));
  return hops().hop_samples;
}

int LinkProfile::samples_for_ms(double ms) const { return static_cast<int>(std::lround(ms * sample_rate_hz / 1000.0)); }

double LinkProfile::tone_amplitude() const {
  if (const auto* w = std::get_if<WordPlan>(&plan)) return w->tones.tone_amplitude;
  return hops().tone_amplitude;
}

int LinkProfile::min_recording_rate_hz() const {
  double top_hz = 0;
  if (const auto* w = std::get_if<WordPlan>(&plan)) {
    top_hz = w->tones.band_low_hz[3] + (w->tones.tones_per_band - 1) * w->tones.step_hz;
  } else {
    const HopPlan& h = hops();
    for (const auto& chord : h.band_first_bin) {
      for (int first_bin : chord)
        top_hz = std::max(top_hz,
                          (first_bin + h.tones_per_band - 1) * static_cast<double>(sample_rate_hz) / h.window_samples);
    }
  }
  return static_cast<int>(2 * top_hz) + 1;
}

const LinkProfile& seed_profile() {
  static const LinkProfile profile = make_seed_profile();
  return profile;
}

const LinkProfile& fast_profile() {
  static const LinkProfile profile = make_fast_profile();
  return profile;
}

namespace {
std::vector<const LinkProfile*>& known_profiles() {
  static std::vector<const LinkProfile*> profiles = {&seed_profile(), &fast_profile()};
  return profiles;
}
}  // namespace

const std::vector<const LinkProfile*>& all_profiles() { return known_profiles(); }

const LinkProfile& register_profile(LinkProfile profile) {
  if (profile.name.empty()) throw std::invalid_argument("a profile needs a name");
  for (const LinkProfile* p : known_profiles()) {
    if (p->name == profile.name) throw std::invalid_argument("a profile called '" + profile.name + "' exists already");
  }
  static std::deque<LinkProfile> registered;  // a deque: the addresses handed out stay valid
  known_profiles().push_back(&registered.emplace_back(std::move(profile)));
  return registered.back();
}

std::string profile_names() {
  std::string names;
  for (const LinkProfile* p : all_profiles()) {
    if (!names.empty()) names += ", ";
    names += p->name;
  }
  return names;
}

const LinkProfile& profile_by_name(std::string_view name) {
  for (const LinkProfile* p : all_profiles()) {
    if (p->name == name) return *p;
  }
  throw std::invalid_argument("unknown link profile '" + std::string(name) + "': choose one of " + profile_names());
}

}  // namespace dtmf
