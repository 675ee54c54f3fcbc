// How dtmfctl shows a command's progress: on a terminal one line per frame, rewritten in
// place as the frame goes from sending to its answer (with a progress bar for a sequence);
// when output goes elsewhere, plain lines; with --json, one JSON object per event.
#pragma once

#include <optional>
#include <string>

#include "dtmf/v1/teleop.pb.h"

namespace dtmf::cli {

struct SequencePosition {
  std::string run_id;
  unsigned frames_done = 0;
  unsigned frames_total = 0;
};

class ProgressView {
 public:
  ProgressView(bool json, bool terminal) : json_(json), terminal_(terminal) {}
  void show(const v1::Progress& progress, const std::optional<SequencePosition>& sequence = std::nullopt);
  // Ends an in-place line before something else is printed.
  void finish_line();

 private:
  bool json_;
  bool terminal_;
  bool line_open_ = false;
};

std::string event_name(v1::FrameEvent event);

}  // namespace dtmf::cli
