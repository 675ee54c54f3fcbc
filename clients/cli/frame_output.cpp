#include "frame_output.h"

#include <cstdio>

namespace dtmf::cli {

nlohmann::json frame_json(const link::PlannedFrame& frame) {
  return {{"word", frame.word},
          {"frame", reliability::bit_string(frame.frame)},
          {"crc", reliability::bit_string(reliability::frame_crc(frame.frame), reliability::kCrcBits)},
          {"tones_hz", {frame.tones_hz[0], frame.tones_hz[1], frame.tones_hz[2], frame.tones_hz[3]}}};
}

std::string frame_line(const link::PlannedFrame& frame) {
  char line[160];
  std::snprintf(line, sizeof line, "word %4u (0x%03X)  frame %s  crc %s  tones %7.1f %7.1f %7.1f %7.1f Hz",
                frame.word, frame.word, reliability::bit_string(frame.frame).c_str(),
                reliability::bit_string(reliability::frame_crc(frame.frame), reliability::kCrcBits).c_str(),
                frame.tones_hz[0], frame.tones_hz[1], frame.tones_hz[2], frame.tones_hz[3]);
  return line;
}

std::string event_text(const command::ReceiverEvent& event) {
  using Kind = command::ReceiverEvent::Kind;
  switch (event.kind) {
    case Kind::Reset: return "reset -> mode_select";
    case Kind::ModeSelected: return "mode " + command::mode_name(*event.mode);
    case Kind::Command: return "command " + command::describe(*event.command);
    case Kind::Ignored: return "ignored: " + event.reason;
  }
  return "";
}

nlohmann::json event_json(const command::ReceiverEvent& event) {
  nlohmann::json json{{"kind", command::event_kind_name(event.kind)},
                      {"state", command::state_name(event.state_after)}};
  if (event.mode) json["mode"] = command::mode_name(*event.mode);
  if (event.command) json["command"] = command::describe(*event.command);
  if (!event.reason.empty()) json["reason"] = event.reason;
  return json;
}

}  // namespace dtmf::cli
