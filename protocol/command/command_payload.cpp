#include "command/command_payload.h"

#include <cstdio>
#include <type_traits>

namespace dtmf::command {

namespace {

constexpr int kFieldBits = 12;
constexpr std::uint32_t kFieldMask = (1u << kFieldBits) - 1;

std::uint32_t pack(Word kind, Word a, Word b) {
  return (static_cast<std::uint32_t>(kind) << (2 * kFieldBits)) | (static_cast<std::uint32_t>(a) << kFieldBits) | b;
}

}  // namespace

std::uint32_t encode_payload(const Command& command) {
  return std::visit(
      [](const auto& c) -> std::uint32_t {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, Reset>) {
          return pack(kResetWord, 0, 0);
        } else if constexpr (std::is_same_v<T, Stop>) {
          return pack(static_cast<Word>(Mode::Stop), 0, 0);
        } else if constexpr (std::is_same_v<T, DriveForDuration>) {
          return pack(static_cast<Word>(Mode::DriveForDuration), encode_field(kSpeedField12, c.speed_percent),
                      encode_field(kDurationField12, c.duration_s));
        } else if constexpr (std::is_same_v<T, TurnForDuration>) {
          return pack(static_cast<Word>(Mode::TurnForDuration), encode_field(kRotationField12, c.rotation_percent),
                      encode_field(kDurationField12, c.duration_s));
        } else if constexpr (std::is_same_v<T, DriveForward>) {
          return pack(static_cast<Word>(Mode::DriveForward), encode_field(kSpeedField12, c.speed_percent), 0);
        } else {
          return pack(static_cast<Word>(Mode::Turn), encode_field(kRotationField12, c.rotation_percent), 0);
        }
      },
      command);
}

ParameterDecode decode_payload(std::uint32_t payload) {
  const Word kind = static_cast<Word>((payload >> (2 * kFieldBits)) & 0xF);
  const Word a = static_cast<Word>((payload >> kFieldBits) & kFieldMask);
  const Word b = static_cast<Word>(payload & kFieldMask);
  auto refuse = [&](const char* what) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "payload 0x%07X: %s", payload, what);
    return ParameterDecode{std::nullopt, buf};
  };
  const bool b_unused = b == 0;
  if (kind == kResetWord) return a == 0 && b_unused ? ParameterDecode{Reset{}, {}} : refuse("RESET with fields");
  const auto mode = mode_from_word(kind);
  if (!mode || *mode == Mode::ModeSelect) return refuse("kind is not a command");
  switch (*mode) {
    case Mode::Stop:
      return a == 0 && b_unused ? ParameterDecode{Stop{}, {}} : refuse("STOP with fields");
    case Mode::DriveForDuration:
    case Mode::TurnForDuration: {
      const bool drive = *mode == Mode::DriveForDuration;
      const auto value = decode_field(drive ? kSpeedField12 : kRotationField12, a);
      const auto duration = decode_field(kDurationField12, b);
      if (!value || !duration) return refuse("no valid field A or duration");
      if (drive) return {DriveForDuration{*value, *duration}, {}};
      return {TurnForDuration{*value, *duration}, {}};
    }
    case Mode::DriveForward:
    case Mode::Turn: {
      const bool drive = *mode == Mode::DriveForward;
      const auto value = decode_field(drive ? kSpeedField12 : kRotationField12, a);
      if (!value || !b_unused) return refuse("no valid field A, or a field B");
      if (drive) return {DriveForward{*value}, {}};
      return {Turn{*value}, {}};
    }
    case Mode::ModeSelect:
      break;
  }
  return refuse("kind is not a command");
}

Command quantised_payload(const Command& command) { return *decode_payload(encode_payload(command)).command; }

}  // namespace dtmf::command
