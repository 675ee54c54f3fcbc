#include "link/frame_reading.h"

#include <algorithm>
#include <array>

#include "reliability/renewal_frame.h"
#include "security/frame_mac.h"
#include "security/freshness.h"

namespace dtmf::link::reading {

namespace {

// The address a frame's bits name, read even where its check failed (its top three bits).
std::uint8_t address_read(const reliability::FrameBits& bits, int bit_count) {
  return static_cast<std::uint8_t>((bits.value() >> (bit_count - reliability::kAddressBits)) &
                                   reliability::kAddressMask);
}

// A Stop in synchronisation form carries no payload: its MAC is over STOP (a Stop always
// carries its whole counter, so that a robot out of step can place it: fast_link.cpp).
const std::uint32_t kStopPayload = command::encode_payload(command::Stop{});
// A stop for every robot under the room key: its MAC covers the payload the room key's
// frames always mean.
const std::uint32_t kRoomStopPayload = command::encode_payload(command::Stop{true});

// The counter a frame stands for, after the last accepted: a synchronisation carries all of
// it, a command its low bits (security/freshness.h).
std::uint64_t completed_counter(const reliability::SealedFrame& f, std::uint64_t last_accepted) {
  return f.form == reliability::SealedForm::Sync
             ? f.counter
             : security::complete_counter(last_accepted, static_cast<std::uint32_t>(f.counter));
}

bool mac_holds(const security::LinkKey& key, const reliability::SealedFrame& f, std::uint64_t counter,
               std::uint32_t payload) {
  return security::frame_mac(key, sealed_mac_input(f, counter, payload)) == f.mac;
}

// The payload `frame`'s MAC holds for under `key` at `counter`: a command's own; in
// synchronisation form a synchronisation's (0) or a Stop's, tried in that order (both holding
// is a 2^-64 chance: the synchronisation, which executes nothing, is the safer reading).
std::optional<std::uint32_t> own_payload(const security::LinkKey& key, const reliability::SealedFrame& frame,
                                         std::uint64_t counter) {
  if (frame.form == reliability::SealedForm::Command)
    return mac_holds(key, frame, counter, frame.payload) ? std::optional(frame.payload) : std::nullopt;
  if (mac_holds(key, frame, counter, kSyncPayload)) return kSyncPayload;
  if (mac_holds(key, frame, counter, kStopPayload)) return kStopPayload;
  return std::nullopt;
}

// The counter `bits` renews the velocity of counter `renewed` with, if this robot's slot holds.
std::optional<std::uint64_t> renewal_counter(const security::LinkKey& key, const reliability::FrameBits& bits,
                                             std::uint8_t address, std::uint64_t renewed) {
  const auto renewal = reliability::renewal_frame_unpack(bits);
  if (!renewal) return std::nullopt;
  const std::uint64_t counter = security::complete_counter(renewed, renewal->counter_low);
  const std::uint32_t mac = security::frame_mac(key, security::renewal_mac_input(address, counter, renewed)) >>
                            (32 - reliability::kRenewalMacBits);
  const bool holds = std::any_of(renewal->slots.begin(), renewal->slots.end(), [&](const reliability::RenewalSlot& s) {
    return s.address == address && s.mac == mac;
  });
  return holds ? std::optional(counter) : std::nullopt;
}

// By payload first, since no MAC stands behind a 50-bit frame: a stop for every robot and a
// renewal whatever their address, then this robot's own frames.
FrameReading read_plain(const reliability::CommandFrame& frame, const ReadingContext& context) {
  command::ParameterDecode decoded = command::decode_payload(frame.payload);
  if (decoded.command && command::every_robot(*decoded.command)) return PlainRoomStop{frame};
  if (const auto renewal = reliability::plain_renewal_unpack(frame)) {
    const auto slot =
        std::find_if(renewal->slots.begin(), renewal->slots.end(),
                     [&](const reliability::PlainRenewalSlot& s) { return s.address == context.address; });
    if (slot == renewal->slots.end()) return Elsewhere{};
    return PlainRenewal{*renewal, *slot};
  }
  if (frame.address != context.address) return Elsewhere{};
  return PlainCommand{frame, std::move(decoded)};
}

FrameReading read_sealed(const reliability::SealedFrame& frame, const reliability::FrameBits& bits,
                         const ReadingContext& context) {
  const SealedVerification v = verify_sealed(frame, bits, context);
  switch (sealed_kind(v.room_stop, v.command_payload.has_value(), v.renewal_counter.has_value(),
                      frame.address == context.address)) {
    case SealedKind::RoomStop:
      return RoomStop{frame.counter, kRoomStopPayload};
    case SealedKind::OwnCommand:
      if (frame.form == reliability::SealedForm::Sync && *v.command_payload == kSyncPayload)
        return Synchronisation{v.command_counter};
      return SealedCommand{frame.form, v.command_counter, *v.command_payload,
                           command::decode_payload(*v.command_payload)};
    case SealedKind::JointRenewal:
      return JointRenewal{*v.renewal_counter};
    case SealedKind::Unverified:
      return Unverified{context.key ? std::optional(v.command_counter) : std::nullopt};
    case SealedKind::Elsewhere:
      break;
  }
  return Elsewhere{};
}

}  // namespace

security::FrameMacInput sealed_mac_input(const reliability::SealedFrame& frame, std::uint64_t counter,
                                         std::uint32_t payload) {
  return {frame.address, static_cast<std::uint8_t>(frame.form), counter, payload};
}

SealedVerification verify_sealed(const reliability::SealedFrame& frame, const reliability::FrameBits& bits,
                                 const ReadingContext& context) {
  SealedVerification v;
  v.room_stop = context.room_key && frame.form == reliability::SealedForm::Sync &&
                mac_holds(*context.room_key, frame, frame.counter, kRoomStopPayload);
  v.command_counter = completed_counter(frame, context.last_accepted);
  if (!context.key) return v;
  v.command_payload = own_payload(*context.key, frame, v.command_counter);
  if (context.renewable_counter)
    v.renewal_counter = renewal_counter(*context.key, bits, context.address, *context.renewable_counter);
  return v;
}

FrameReading read_frame(const HeardHopFrame& heard, bool sealed, const ReadingContext& context) {
  const int bit_count = sealed ? reliability::kSealedFrameBits : reliability::kCommandFrameBits;
  const Broken broken{address_read(heard.bits, bit_count) == context.address};
  if (!heard.intact) return broken;
  if (context.echoes && context.echoes->is_echo(heard.bits, heard.heard_ms)) return Echo{};
  // The receive path passes as intact only frames whose check holds; one that does not is broken.
  if (sealed) {
    const auto frame = reliability::sealed_frame_unpack(heard.bits);
    return frame ? read_sealed(*frame, heard.bits, context) : FrameReading(broken);
  }
  const auto frame = reliability::command_frame_unpack(heard.bits.low64());
  return frame ? read_plain(*frame, context) : FrameReading(broken);
}

std::string_view kind_name(FrameKind kind) {
  static constexpr std::array<std::string_view, std::variant_size_v<FrameReading>> kNames{
      "broken",    "echo",          "elsewhere",       "plain_command",  "plain_room_stop", "plain_renewal",
      "room_stop", "joint_renewal", "synchronisation", "sealed_command", "unverified"};
  return kNames[static_cast<std::size_t>(kind)];
}

}  // namespace dtmf::link::reading
