#include "frame_output.h"

#include <cmath>
#include <cstdio>

namespace dtmf::cli {

namespace {

std::string check_bits(const reliability::FrameBits& bits, int check_bit_count) {
  return bits.bit_string(check_bit_count);
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
  nlohmann::json json{{"frame", frame.bits.bit_string(frame.bit_count)},
                      {"crc", check_bits(frame.bits, frame.check_bit_count)},
                      {"tones_hz", frame.tones_hz},
                      {"authenticated", frame.authenticated}};
  if (frame.word) json["word"] = *frame.word;
  if (frame.sequence) json["sequence"] = *frame.sequence;
  if (frame.counter) json["counter"] = *frame.counter;
  if (frame.synchronisation) json["synchronisation"] = true;
  return json;
}

std::string frame_line(const link::TransmitFrame& frame) {
  char head[64] = "";
  if (frame.word) std::snprintf(head, sizeof head, "word %4u (0x%03X)  ", *frame.word, *frame.word);
  if (frame.sequence) std::snprintf(head, sizeof head, "seq %2u  ", static_cast<unsigned>(*frame.sequence));
  if (frame.counter) {
    std::snprintf(head, sizeof head, "%s %llu  ", frame.synchronisation ? "sync at counter" : "counter",
                  static_cast<unsigned long long>(*frame.counter));
  }
  return std::string(head) + "frame " + frame.bits.bit_string(frame.bit_count) + "  crc " +
         check_bits(frame.bits, frame.check_bit_count) + "  " + tones_text(frame.tones_hz);
}

nlohmann::json reception_json(const link::Reception& r) {
  nlohmann::json json{{"t_ms", std::lround(r.start_ms)},
                      {"heard_ms", std::lround(r.heard_ms)},
                      {"frame", r.bits.bit_string(r.bit_count)},
                      {"crc", check_bits(r.bits, r.check_bit_count)},
                      {"crc_ok", r.intact},
                      {"tones_hz", r.tones_hz},
                      {"what", r.detail},
                      {"authenticated", r.authenticated}};
  if (r.payload_word) json["word"] = *r.payload_word;
  if (r.sequence) json["sequence"] = *r.sequence;
  if (r.counter) json["counter"] = *r.counter;
  if (r.event != link::ReceptionEvent::Broken) {
    nlohmann::json event{{"kind", link::event_name(r.event)}};
    if (r.refusal != link::RefusalReason::None) event["reason"] = link::reason_name(r.refusal);
    if (!r.command_state.empty()) event["state"] = r.command_state;
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
  if (r.counter) line += "counter " + std::to_string(*r.counter) + "  ";
  if (r.payload_word) {
    char word[32];
    std::snprintf(word, sizeof word, "word %4u (0x%03X)  ", *r.payload_word, *r.payload_word);
    line += word;
  }
  line += r.bits.bit_string(r.bit_count) + "  CRC " + (r.intact ? "ok    " : "FAIL  ");
  if (r.authenticated) line += "MAC ok  ";
  if (r.refusal == link::RefusalReason::Authentication) line += "REFUSED (authentication): ";
  return line + (r.detail.empty() ? "(rejected)" : r.detail);
}

}  // namespace dtmf::cli
