#include "frame_output.h"

#include <cmath>
#include <cstdio>

#include "reliability/crc4.h"

namespace dtmf::cli {

namespace {

std::string check_bits(std::uint64_t bits, int check_bit_count) {
  return reliability::bit_string(bits & ((std::uint64_t{1} << check_bit_count) - 1), check_bit_count);
}

std::string tones_text(const std::vector<double>& tones_hz) {
  std::string text = "tones";
  for (double hz : tones_hz) {
    char tone[16];
    std::snprintf(tone, sizeof tone, " %7.1f", hz);
    text += tone;
  }
  return text + " Hz";
}

}  // namespace

nlohmann::json frame_json(const link::TransmitFrame& frame) {
  nlohmann::json json{{"frame", reliability::bit_string(frame.bits, frame.bit_count)},
                      {"crc", check_bits(frame.bits, frame.check_bit_count)},
                      {"tones_hz", frame.tones_hz}};
  if (frame.word) json["word"] = *frame.word;
  if (frame.sequence) json["sequence"] = *frame.sequence;
  return json;
}

std::string frame_line(const link::TransmitFrame& frame) {
  char head[64] = "";
  if (frame.word) std::snprintf(head, sizeof head, "word %4u (0x%03X)  ", *frame.word, *frame.word);
  if (frame.sequence) std::snprintf(head, sizeof head, "seq %2u  ", static_cast<unsigned>(*frame.sequence));
  return std::string(head) + "frame " + reliability::bit_string(frame.bits, frame.bit_count) + "  crc " +
         check_bits(frame.bits, frame.check_bit_count) + "  " + tones_text(frame.tones_hz);
}

nlohmann::json reception_json(const link::Reception& r) {
  nlohmann::json json{{"t_ms", std::lround(r.start_ms)},
                      {"heard_ms", std::lround(r.heard_ms)},
                      {"frame", reliability::bit_string(r.bits, r.bit_count)},
                      {"crc", check_bits(r.bits, r.check_bit_count)},
                      {"crc_ok", r.intact},
                      {"tones_hz", r.tones_hz},
                      {"what", r.detail}};
  if (r.word) json["word"] = *r.word;
  if (r.sequence) json["sequence"] = *r.sequence;
  if (!r.event.empty()) {
    nlohmann::json event{{"kind", r.event}};
    if (!r.state_after.empty()) event["state"] = r.state_after;
    if (r.command) event["command"] = command::describe(*r.command);
    json["event"] = event;
  }
  return json;
}

std::string reception_line(const link::Reception& r) {
  char time[32];
  std::snprintf(time, sizeof time, "%8.3f s  ", r.start_ms / 1000.0);
  std::string line = time;
  if (r.sequence) line += "seq " + std::to_string(*r.sequence) + "  ";
  if (r.word) {
    char word[32];
    std::snprintf(word, sizeof word, "word %4u (0x%03X)  ", *r.word, *r.word);
    line += word;
  }
  return line + reliability::bit_string(r.bits, r.bit_count) + "  CRC " + (r.intact ? "ok    " : "FAIL  ") +
         (r.detail.empty() ? "(rejected)" : r.detail);
}

}  // namespace dtmf::cli
