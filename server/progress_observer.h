// Who else hears a command's progress: the transmitter hands every ProgressEvent it emits to
// its observer before the caller's stream sees it, so a record kept by the observer is
// queued before the caller learns the outcome. Called on the transmitter's threads (Queued
// on the submitting caller's thread, under the transmitter's lock): keep it quick.
#pragma once

#include "job.h"

namespace dtmf::server {

class ProgressObserver {
 public:
  virtual ~ProgressObserver() = default;
  virtual void observe(const Job& job, const ProgressEvent& event) = 0;
};

}  // namespace dtmf::server
