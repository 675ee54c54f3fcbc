#include "command/command_payload.h"
#include "command/overloaded.h"

#include <cstdio>

namespace dtmf::command {

namespace {

constexpr int kFieldBits = 12;
constexpr std::uint32_t kFieldMask = (1u << kFieldBits) - 1;
constexpr std::uint32_t kKindMask = 0x7;

std::uint32_t pack(PayloadKind kind, Word a, Word b) {
  return (static_cast<std::uint32_t>(kind) << (2 * kFieldBits)) | (static_cast<std::uint32_t>(a) << kFieldBits) | b;
}

}  // namespace

std::uint32_t encode_payload(const Command& command) {
  return std::visit(
      Overloaded{
          [](const Reset&) { return pack(PayloadKind::Reset, 0, 0); },
          [](const Stop& c) { return pack(PayloadKind::Stop, c.every_robot ? kEveryRobotField : 0, 0); },
          [](const DriveForDuration& c) {
            return pack(PayloadKind::DriveForDuration, encode_field(kSpeedField12, c.speed_percent),
                        encode_field(kDurationField12, c.duration_s));
          },
          [](const TurnForDuration& c) {
            return pack(PayloadKind::TurnForDuration, encode_field(kRotationField12, c.rotation_percent),
                        encode_field(kDurationField12, c.duration_s));
          },
          [](const DriveForward& c) {
            return pack(PayloadKind::DriveForward, encode_field(kSpeedField12, c.speed_percent), 0);
          },
          [](const Turn& c) { return pack(PayloadKind::Turn, encode_field(kRotationField12, c.rotation_percent), 0); },
          [](const Velocity& c) {
            const Word angular = encode_field(kAngularFraction8, c.angular_fraction);
            const Word lease = encode_field_at_most(kLeaseField4, c.lease_s);
            return pack(PayloadKind::Velocity, encode_field(kLinearFraction12, c.linear_fraction),
                        static_cast<Word>((angular << kLeaseField4.bits) | lease));
          }},
      command);
}

ParameterDecode decode_payload(std::uint32_t payload) {
  const auto kind = static_cast<PayloadKind>((payload >> (2 * kFieldBits)) & kKindMask);
  const Word a = static_cast<Word>((payload >> kFieldBits) & kFieldMask);
  const Word b = static_cast<Word>(payload & kFieldMask);
  auto refuse = [&](const char* what) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "payload 0x%07X: %s", payload, what);
    return ParameterDecode{std::nullopt, buf};
  };
  if (payload >> kPayloadBits) return refuse("wider than a payload");
  switch (kind) {
    case PayloadKind::Reset:
      return a == 0 && b == 0 ? ParameterDecode{Reset{}, {}} : refuse("RESET with fields");
    case PayloadKind::Stop:
      if (b != 0 || (a != 0 && a != kEveryRobotField)) return refuse("STOP with fields");
      return {Stop{a == kEveryRobotField}, {}};
    case PayloadKind::DriveForDuration:
    case PayloadKind::TurnForDuration: {
      const bool drive = kind == PayloadKind::DriveForDuration;
      const auto value = decode_field(drive ? kSpeedField12 : kRotationField12, a);
      const auto duration = decode_field(kDurationField12, b);
      if (!value || !duration) return refuse("no valid field A or duration");
      if (drive) return {DriveForDuration{*value, *duration}, {}};
      return {TurnForDuration{*value, *duration}, {}};
    }
    case PayloadKind::DriveForward:
    case PayloadKind::Turn: {
      const bool drive = kind == PayloadKind::DriveForward;
      const auto value = decode_field(drive ? kSpeedField12 : kRotationField12, a);
      if (!value || b != 0) return refuse("no valid field A, or a field B");
      if (drive) return {DriveForward{*value}, {}};
      return {Turn{*value}, {}};
    }
    case PayloadKind::Velocity: {
      const auto linear = decode_field(kLinearFraction12, a);
      const auto angular = decode_field(kAngularFraction8, static_cast<Word>(b >> kLeaseField4.bits));
      const auto lease = decode_field(kLeaseField4, static_cast<Word>(b & ((1u << kLeaseField4.bits) - 1)));
      if (!linear || !angular || !lease) return refuse("VELOCITY without a valid linear, angular or lease field");
      return {Velocity{*linear, *angular, *lease}, {}};
    }
    case PayloadKind::Extended:
      return refuse("a kind this robot does not know yet (reserved)");
  }
  return refuse("kind is not a command");
}

Command quantised_payload(const Command& command) { return *decode_payload(encode_payload(command)).command; }

}  // namespace dtmf::command
