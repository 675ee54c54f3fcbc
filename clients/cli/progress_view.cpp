#include "progress_view.h"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace dtmf::cli {

std::string event_name(v1::FrameEvent event) {
  std::string name = v1::FrameEvent_Name(event);
  // A newer server's event this client does not know has no name: its number then.
  if (name.rfind("FRAME_EVENT_", 0) != 0) return "event_" + std::to_string(static_cast<int>(event));
  name = name.substr(std::string("FRAME_EVENT_").size());
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

namespace {

std::string bar(const SequencePosition& s) {
  constexpr int kWidth = 20;
  const int filled = s.frames_total ? static_cast<int>(kWidth * s.frames_done / s.frames_total) : 0;
  char text[64];
  std::snprintf(text, sizeof text, "[%s%s] %2u/%u ", std::string(static_cast<std::size_t>(filled), '#').c_str(),
                std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), s.frames_done, s.frames_total);
  return text;
}

std::string describe(const v1::Progress& p) {
  char text[256];
  switch (p.event()) {
    case v1::FRAME_EVENT_QUEUED:
      std::snprintf(text, sizeof text, "%s: queued (%u ahead)", p.command().c_str(), p.queue_position());
      return text;
    case v1::FRAME_EVENT_WAITING_FOR_AIR:
      // The sender listens before it talks; it says what holds the frame, and for how long at most.
      std::snprintf(text, sizeof text, "%s: frame %u/%u waiting for the air: %s (at most %.1f s)", p.command().c_str(),
                    p.frame_index() + 1, p.frame_count(), p.air_wait_reason().c_str(), p.air_wait_left_ms() / 1000);
      return text;
    case v1::FRAME_EVENT_CONFIRMED:
    case v1::FRAME_EVENT_CONTINUED:
    case v1::FRAME_EVENT_FAILED:
    case v1::FRAME_EVENT_SENT:
      return p.command() + ": " + event_name(p.event()) + (p.detail().empty() ? "" : " (" + p.detail() + ")");
    default:
      break;
  }
  std::string state = event_name(p.event());
  if (p.event() == v1::FRAME_EVENT_ACK || p.event() == v1::FRAME_EVENT_NACK) {
    char ms[32];
    std::snprintf(ms, sizeof ms, " after %.0f ms", p.response_time_ms());
    state = (p.event() == v1::FRAME_EVENT_ACK ? "ACK" : "NACK") + std::string(ms);
  }
  if (p.event() == v1::FRAME_EVENT_TRANSMITTING || p.event() == v1::FRAME_EVENT_RETRANSMITTING) {
    state += " (attempt " + std::to_string(p.attempt()) + ")";
    if (p.air_wait_ms() > 0) {
      char waited[48];
      std::snprintf(waited, sizeof waited, " after %.1f s waiting for the air", p.air_wait_ms() / 1000);
      state += waited;
    }
  }
  std::string tones;
  for (double hz : p.tones_hz()) {
    char t[16];
    std::snprintf(t, sizeof t, " %.0f", hz);
    tones += t;
  }
  // A seed frame carries a word; a fast frame a whole command, named by its sequence number,
  // or with a key authenticated by a MAC (a synchronisation of the counter goes first now and then).
  char label[24];
  if (p.has_word())
    std::snprintf(label, sizeof label, "word %4u", p.word());
  else if (p.synchronisation())
    std::snprintf(label, sizeof label, "sync");
  else if (p.authenticated())
    std::snprintf(label, sizeof label, "MAC");
  else
    std::snprintf(label, sizeof label, "seq %2u", p.sequence());
  std::snprintf(text, sizeof text, "frame %u/%u %s %s tones%s Hz  %s", p.frame_index() + 1, p.frame_count(), label,
                p.frame_bits().c_str(), tones.c_str(), state.c_str());
  return text;
}

// Events after which the frame's line is complete.
bool closes_line(v1::FrameEvent e) {
  return e == v1::FRAME_EVENT_ACK || e == v1::FRAME_EVENT_NACK || e == v1::FRAME_EVENT_NO_ANSWER ||
         e == v1::FRAME_EVENT_AWAITING_DECISION || e == v1::FRAME_EVENT_QUEUED ||
         e == v1::FRAME_EVENT_WAITING_FOR_AIR || e == v1::FRAME_EVENT_CONFIRMED || e == v1::FRAME_EVENT_CONTINUED ||
         e == v1::FRAME_EVENT_FAILED || e == v1::FRAME_EVENT_SENT;
}

}  // namespace

void ProgressView::finish_line() {
  if (line_open_) std::printf("\n");
  line_open_ = false;
  std::fflush(stdout);
}

void ProgressView::show(const v1::Progress& p, const std::optional<SequencePosition>& sequence) {
  if (json_) {
    nlohmann::json event{{"event", event_name(p.event())},
                         {"command_id", p.command_id()},
                         {"command", p.command()},
                         {"frame_index", p.frame_index()},
                         {"frame_count", p.frame_count()},
                         {"attempt", p.attempt()},
                         {"profile", p.profile()},
                         {"frame", p.frame_bits()},
                         {"tones_hz", std::vector<double>(p.tones_hz().begin(), p.tones_hz().end())},
                         {"time_unix_ms", p.time_unix_ms()}};
    event["robot"] = p.robot();
    if (p.has_word()) event["word"] = p.word();
    if (p.has_sequence()) event["sequence"] = p.sequence();
    if (p.event() != v1::FRAME_EVENT_QUEUED) event["authenticated"] = p.authenticated();
    if (p.synchronisation()) event["synchronisation"] = true;
    if (p.event() == v1::FRAME_EVENT_ACK || p.event() == v1::FRAME_EVENT_NACK)
      event["response_time_ms"] = p.response_time_ms();
    if (p.event() == v1::FRAME_EVENT_ACK || p.event() == v1::FRAME_EVENT_CONFIRMED)
      event["answer_authenticated"] = p.answer_authenticated();
    if (!p.detail().empty()) event["detail"] = p.detail();
    if (!p.air_wait_reason().empty()) event["air_wait_reason"] = p.air_wait_reason();
    if (p.event() == v1::FRAME_EVENT_WAITING_FOR_AIR) event["air_wait_left_ms"] = p.air_wait_left_ms();
    if (p.air_wait_ms() > 0) event["air_wait_ms"] = p.air_wait_ms();
    if (sequence) {
      event["run_id"] = sequence->run_id;
      event["frames_done"] = sequence->frames_done;
      event["frames_total"] = sequence->frames_total;
    }
    std::printf("%s\n", event.dump().c_str());
    std::fflush(stdout);
    return;
  }
  const std::string line = (sequence ? bar(*sequence) : "") + describe(p);
  if (terminal_) {
    std::printf("\r\033[K%s", line.c_str());
    line_open_ = true;
    if (closes_line(p.event())) finish_line();
    std::fflush(stdout);
  } else {
    // Line by line into a pipe or a log too: a script reading it reacts to each frame as it
    // happens, not when the command ends.
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  }
}

}  // namespace dtmf::cli
