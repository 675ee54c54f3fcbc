#include "link_health.h"

#include <cmath>
#include <cstdio>

namespace dtmf::ros_bridge {
namespace {

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string seconds_ago(std::optional<double> at_ms, double now_ms) {
  return at_ms ? fixed((now_ms - *at_ms) / 1000.0, 1) : "never";
}

}  // namespace

void LinkHealth::on_reading(const LinkReading& reading, double now_ms) {
  if (reading.answered) {
    last_answer_ms_ = now_ms;
    unanswered_in_a_row_ = 0;
  } else if (reading.unanswered) {
    ++unanswered_in_a_row_;
  }
  last_ = reading;
  last_reading_ms_ = now_ms;
}

HealthReport LinkHealth::report(StreamState stream, double now_ms) const {
  HealthReport r;
  const bool driving = stream == StreamState::Open || stream == StreamState::Stopping;
  if (!last_) {
    r.message = "no frame sent yet";
  } else {
    const int answered = static_cast<int>(std::lround(last_->link_quality * last_->frames_in_window));
    const std::string counts = std::to_string(answered) + " of " + std::to_string(last_->frames_in_window) +
                               " frames answered in the last " + fixed(last_->window_s, 0) + " s";
    if (unanswered_in_a_row_ >= kErrorUnanswered) {
      r.level = HealthLevel::Error;
      r.message = "not answering: the last " + std::to_string(unanswered_in_a_row_) + " frames unanswered";
    } else if (last_->frames_in_window == 0) {
      // The server's window holds no ended frame yet (a stream's first response): nothing lost.
      r.message = "no frame ended in the last " + fixed(last_->window_s, 0) + " s";
    } else if (last_->link_quality < 1.0) {
      r.level = HealthLevel::Warn;
      r.message = "answers lost: " + counts;
    } else {
      r.message = "answering: " + counts;
    }
    if (!driving) r.message += " (measured " + seconds_ago(last_reading_ms_, now_ms) + " s ago; not driving now)";
    r.values = {
        {"link quality", fixed(last_->link_quality, 2)},
        {"frames in window", std::to_string(last_->frames_in_window)},
        {"window s", fixed(last_->window_s, 1)},
        {"response time ms", fixed(last_->response_time_ms, 0)},
        {"lease s", fixed(last_->lease_s, 2)},
        {"lease left s", fixed(driving ? last_->lease_left_s : 0.0, 2)},
    };
  }
  r.values.insert(r.values.begin(), {"last answer s ago", seconds_ago(last_answer_ms_, now_ms)});
  r.values.insert(r.values.begin(), {"stream", to_string(stream)});
  return r;
}

}  // namespace dtmf::ros_bridge
