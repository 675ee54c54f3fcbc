// The fast profile's frames as its sender plays them (fast_frames.h): each kind packs its
// bits, spreads them over its code's symbols, and sounds them as hopped chords.
#include "link/fast_frames.h"

#include <algorithm>
#include <span>

#include "link/reply_lane.h"
#include "reliability/sealed_frame.h"
#include "security/freshness.h"
#include "signal/hop_synthesizer.h"

namespace dtmf::link {

namespace {

static_assert(security::kAnswerTagBytes == reliability::kTagBytes);

// Gives `f` the tones and audio of `symbols`, and how long they sound.
void sound(TransmitFrame& f, const LinkProfile& profile, std::span<const std::uint8_t> symbols) {
  f.tones_hz = signal::frame_tones_hz(profile, symbols);
  f.audio = signal::synthesize_hopped_frame(profile, symbols);
  f.tone_ms = 1000.0 * static_cast<double>(f.audio.size()) / profile.sample_rate_hz;
}

}  // namespace

reliability::TagChordSymbols reply_tag(const security::LinkKey& key, const security::FrameMacInput& input,
                                       std::uint32_t mac, const reliability::BandValueSet& taken) {
  return reliability::tag_chord_symbols(security::answer_tag(key, input, mac), taken);
}

TransmitFrame command_transmit_frame(const LinkProfile& profile, const reliability::CommandFrame& frame) {
  TransmitFrame f;
  f.bits = reliability::command_frame_pack(frame);
  f.bit_count = reliability::kCommandFrameBits;
  f.check_bit_count = reliability::kCommandCrcBits;
  f.sequence = frame.sequence;
  f.address = frame.address;
  f.answer_lane = answer_lane(frame.sequence);
  sound(f, profile, reliability::command_frame_symbols(f.bits.low64()));
  f.next_frame_after_ms = f.tone_ms + profile.timing.gap_ms;  // its answer sounds in the reply bands
  return f;
}

TransmitFrame sealed_transmit_frame(const LinkProfile& profile, const security::LinkKey& key,
                                    const SealedContent& content) {
  const auto form = content.synchronisation ? reliability::SealedForm::Sync : reliability::SealedForm::Command;
  const security::FrameMacInput input{content.address, static_cast<std::uint8_t>(form), content.counter,
                                      content.payload};
  reliability::SealedFrame frame;
  frame.address = content.address;
  frame.form = form;
  frame.counter = content.synchronisation ? content.counter : security::counter_low_bits(content.counter);
  frame.payload = content.payload;
  frame.mac = security::frame_mac(key, input);
  TransmitFrame f;
  f.bits = reliability::sealed_frame_pack(frame);
  f.bit_count = reliability::kSealedFrameBits;
  f.check_bit_count = reliability::kSealedCheckBits;
  f.address = frame.address;
  f.authenticated = true;
  f.synchronisation = content.synchronisation;
  f.counter = content.counter;
  f.answer_lane = answer_lane(content.counter);
  const auto symbols = reliability::sealed_frame_symbols(f.bits);
  f.sent_tones = reliability::tag_chord_taken(symbols);
  f.answer_tag = reply_tag(key, input, frame.mac, f.sent_tones);
  sound(f, profile, symbols);
  // Its tag chord sounds in the frame bands: no next frame until it has.
  f.next_frame_after_ms =
      std::max(f.tone_ms + profile.timing.gap_ms, profile.hops().sealed_bands_busy_ms(profile.sample_rate_hz));
  return f;
}

TransmitFrame renewal_transmit_frame(const LinkProfile& profile, const reliability::RenewalFrame& renewal,
                                     std::uint64_t counter) {
  TransmitFrame f;
  f.bits = reliability::renewal_frame_pack(renewal);
  f.bit_count = reliability::kSealedFrameBits;
  f.check_bit_count = reliability::kSealedCheckBits;
  f.address = renewal.slots[0].address;
  f.authenticated = true;
  f.renewal = true;
  f.counter = counter;
  sound(f, profile, reliability::sealed_frame_symbols(f.bits));
  f.next_frame_after_ms = f.tone_ms + profile.timing.gap_ms;  // no answer to wait for
  return f;
}

}  // namespace dtmf::link
