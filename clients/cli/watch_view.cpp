#include "watch_view.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

namespace dtmf::cli {

namespace {

template <class... Args>
std::string format(const char* pattern, Args... args) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

std::string robots_of(const v1::FramePlayed& f) {
  if (f.robots().empty()) return "every robot";
  std::string all;
  for (const auto& r : f.robots()) all += (all.empty() ? "" : ",") + r;
  return all;
}

std::string frame_line(const v1::FramePlayed& f) {
  std::string line = format("frame     %-12s %s", robots_of(f).c_str(), f.command().c_str());
  if (f.kind() != "command") line += " [" + f.kind() + "]";
  line += format(" %s, frame %u/%u", f.profile().c_str(), f.frame_index() + 1, f.frame_count());
  if (f.attempt() > 1) line += format(", attempt %u", f.attempt());
  if (f.has_sequence()) line += format(", sequence %u", f.sequence());
  if (f.has_counter()) line += format(", counter %llu", static_cast<unsigned long long>(f.counter()));
  line += f.authenticated() ? ", authenticated" : ", no MAC";
  if (f.air_wait_ms() > 0) line += format(", waited %.0f ms for the air", f.air_wait_ms());
  return line;
}

std::string answered_line(const v1::FrameAnswered& a) {
  std::string line = format("answered  %-12s frame %u attempt %u: %s", a.robot().c_str(), a.frame_index() + 1,
                            a.attempt(), a.answer().c_str());
  if (a.answer() == "ack") line += a.authenticated() ? " (authenticated)" : " (untagged)";
  if (a.has_response_time_ms()) line += format(" after %.0f ms", a.response_time_ms());
  return line;
}

std::string heard_line(const v1::AnswerHeard& h) {
  std::string line = format("heard     %-12s %s %s", h.robot().empty() ? "-" : h.robot().c_str(),
                            h.ack() ? "ACK" : "NACK", h.profile().c_str());
  if (h.has_sequence()) line += format(", sequence %u", h.sequence());
  if (h.has_address()) line += format(", address %u", h.address());
  if (h.tagged()) line += ", tag chord";
  return line + format(", %.1f dBFS", h.level_dbfs());
}

std::string spectrum_line(const v1::SpectrumColumn& c) {
  const auto& bins = c.level_dbfs();
  if (bins.empty()) return "spectrum  (no bins)";
  const auto loudest = std::max_element(bins.begin(), bins.end());
  const auto at = static_cast<double>(loudest - bins.begin());
  return format("spectrum  %.0f-%.0f Hz in %d bins: loudest %.1f dBFS at %.0f Hz", c.low_hz(),
                c.low_hz() + c.step_hz() * bins.size(), static_cast<int>(bins.size()), *loudest,
                c.low_hz() + c.step_hz() * (at + 0.5));
}

std::string event_line(const v1::WatchAirResponse& m) {
  switch (m.event_case()) {
    case v1::WatchAirResponse::kFramePlayed:
      return frame_line(m.frame_played());
    case v1::WatchAirResponse::kFrameAnswered:
      return answered_line(m.frame_answered());
    case v1::WatchAirResponse::kAnswerHeard:
      return heard_line(m.answer_heard());
    case v1::WatchAirResponse::kAirWaiting:
      return format("waiting   %-12s for the air: %s (at most %.1f s more)", m.air_waiting().robot().c_str(),
                    m.air_waiting().reason().c_str(), m.air_waiting().left_ms() / 1000);
    case v1::WatchAirResponse::kAirBusy:
      return m.air_busy().busy() ? format("air       busy: %.1f dBFS over a floor of %.1f dBFS",
                                          m.air_busy().level_dbfs(), m.air_busy().floor_dbfs())
                                 : std::string("air       quiet again");
    case v1::WatchAirResponse::kCommandEnded: {
      const v1::CommandEnded& e = m.command_ended();
      std::string line = format("ended     %-12s %s: %s", e.robot().empty() ? "every robot" : e.robot().c_str(),
                                e.command().c_str(), e.outcome().c_str());
      return e.detail().empty() ? line : line + " (" + e.detail() + ")";
    }
    case v1::WatchAirResponse::kSpectrum:
      return spectrum_line(m.spectrum());
    default:
      return "(an event this dtmfctl does not know: update it)";
  }
}

}  // namespace

std::string watch_lines(const v1::WatchAirResponse& message) {
  std::string lines;
  if (message.dropped_events() > 0 || message.dropped_columns() > 0)
    lines += format("(this watcher read too slowly: lost %llu events and %llu spectrum columns)\n",
                    static_cast<unsigned long long>(message.dropped_events()),
                    static_cast<unsigned long long>(message.dropped_columns()));
  return lines + format("%10.1f ms  ", message.audio_ms()) + event_line(message) + "\n";
}

std::string json_line(const google::protobuf::Message& message) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json + "\n";
}

std::string watch_json(const v1::WatchAirResponse& message) { return json_line(message); }

std::string reception_line(const v1::Reception& r) {
  const std::time_t seconds = static_cast<std::time_t>(r.heard_unix_ms() / 1000);
  std::tm local{};
  localtime_r(&seconds, &local);
  char clock[16];
  std::strftime(clock, sizeof clock, "%H:%M:%S", &local);
  std::string robot = !r.robot().empty() ? r.robot()
                      : r.has_address()  ? "address " + std::to_string(r.address())
                                         : r.host();
  std::vector<std::string> said;
  if (!r.reason().empty()) said.push_back(r.reason());
  if (!r.command().empty()) said.push_back(r.command());
  if (r.has_linear_mps()) said.push_back(format("%.2f m/s %.2f rad/s", r.linear_mps(), r.angular_radps()));
  if (r.authenticated()) said.push_back("authenticated");
  said.push_back(r.reply().empty() ? "not answered" : "answered " + r.reply());
  std::string line = format("%s.%03lld  %-12s %-5s %-9s ", clock, static_cast<long long>(r.heard_unix_ms() % 1000),
                            robot.c_str(), r.profile().c_str(), r.event().c_str());
  for (std::size_t i = 0; i < said.size(); ++i) line += (i ? ", " : "") + said[i];
  return line + "\n";
}

}  // namespace dtmf::cli
