// dtmfctl teleop's full-screen terminal view (ncurses): target and confirmed velocities, the
// last response time, a link-quality bar, the lease left, the last frame's event and the
// keys. Owns the terminal while it lives (cbreak, no echo, keys read with a timeout) and
// gives it back as it was when destroyed, also on an exception.
#pragma once

#include <optional>
#include <string>

#include "dtmf/v1/teleop.pb.h"
#include "teleop_keys.h"

namespace dtmf::cli {

struct TeleopView {
  std::string server;
  std::string profile;
  std::string robot;
  double lease_s = 1.0;
  TeleopTarget target;
  std::optional<v1::TeleopResponse> status;  // the newest from the server
  std::string note;                          // a line for the person: a stop sent, an error
};

class TeleopScreen {
 public:
  TeleopScreen();
  ~TeleopScreen();
  TeleopScreen(const TeleopScreen&) = delete;
  TeleopScreen& operator=(const TeleopScreen&) = delete;

  void draw(const TeleopView& view);
  // The next key, or nothing within `timeout_ms`.
  std::optional<int> key(int timeout_ms);
};

}  // namespace dtmf::cli
