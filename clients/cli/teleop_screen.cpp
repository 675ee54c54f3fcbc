#include "teleop_screen.h"

#include <ncurses.h>

#include <cmath>
#include <cstdio>

namespace dtmf::cli {

namespace {

constexpr int kBarWidth = 20;

void line(int row, const char* fmt, auto... args) {
  char text[256];
  std::snprintf(text, sizeof text, fmt, args...);
  mvaddstr(row, 0, text);
  clrtoeol();
}

std::string bar(double fraction) {
  const int filled = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * kBarWidth));
  return "[" + std::string(static_cast<std::size_t>(filled), '#') +
         std::string(static_cast<std::size_t>(kBarWidth - filled), '-') + "]";
}

const char* event_name(v1::FrameEvent event) {
  switch (event) {
    case v1::FRAME_EVENT_TRANSMITTING:
      return "on air";
    case v1::FRAME_EVENT_ACK:
      return "ACK";
    case v1::FRAME_EVENT_NACK:
      return "NACK";
    case v1::FRAME_EVENT_NO_ANSWER:
      return "no answer";
    case v1::FRAME_EVENT_FAILED:
      return "failed";
    case v1::FRAME_EVENT_WAITING_FOR_AIR:
      return "waiting for the air";
    default:
      return "";
  }
}

}  // namespace

TeleopScreen::TeleopScreen() {
  initscr();
  cbreak();
  noecho();
  keypad(stdscr, TRUE);
  curs_set(0);
}

TeleopScreen::~TeleopScreen() { endwin(); }

std::optional<int> TeleopScreen::key(int timeout_ms) {
  timeout(timeout_ms);
  const int k = getch();
  if (k == ERR) return std::nullopt;
  return k;
}

void TeleopScreen::draw(const TeleopView& v) {
  int row = 0;
  line(row++, "dtmfctl teleop  server %s  profile %s  robot %s  lease %.2f s", v.server.c_str(), v.profile.c_str(),
       v.robot.c_str(), v.lease_s);
  row++;
  line(row++, "                 target     confirmed");
  const bool confirmed = v.status && v.status->confirmed();
  const auto confirmed_text = [&](double value) {
    char text[32];
    if (confirmed)
      std::snprintf(text, sizeof text, "%+9.3f", value);
    else
      std::snprintf(text, sizeof text, "%9s", "-");
    return std::string(text);
  };
  line(row++, "linear   m/s   %+9.3f  %s", v.target.linear_mps,
       confirmed_text(v.status ? v.status->confirmed_linear_mps() : 0).c_str());
  line(row++, "angular  rad/s %+9.3f  %s", v.target.angular_radps,
       confirmed_text(v.status ? v.status->confirmed_angular_radps() : 0).c_str());
  row++;
  if (v.status && v.status->response_time_ms() > 0)
    line(row++, "response       %.0f ms", v.status->response_time_ms());
  else
    line(row++, "response       -");
  const double quality = v.status ? v.status->link_quality() : 0;
  line(row++, "link           %s %3.0f %%  (%u frames in %.0f s)", bar(quality).c_str(), 100 * quality,
       v.status ? v.status->frames_in_window() : 0u, v.status ? v.status->link_window_s() : 0.0);
  line(row++, "lease left     %.2f s", v.status ? v.status->lease_left_s() : 0.0);
  if (v.status && v.status->has_progress()) {
    const auto& p = v.status->progress();
    line(row++, "last frame     %s %s", event_name(p.event()), p.command().c_str());
  } else {
    line(row++, "last frame     -");
  }
  row++;
  line(row++,
       "keys: w/x linear +-%.2f m/s   a/d angular +-%.1f rad/s   s/space stop   e stop every robot   q quit (with a "
       "stop)",
       kLinearStep_mps, kAngularStep_radps);
  line(row++, "%s", v.note.c_str());
  refresh();
}

}  // namespace dtmf::cli
