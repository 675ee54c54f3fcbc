// TeleopService::WatchAir: the air's fan-out (air_fanout.h) as a server stream, one small
// reactor per watcher in the manner of gRPC's route_guide callback server: no thread and no
// sleep of its own. A write starts when the watcher's queue gains an entry (on the publisher's
// thread, which it never holds up) or when the last write is done (on gRPC's); while a write is
// in flight new entries wait in the queue, where a slow reader loses the oldest, and the next
// message says how many.
#pragma once

#include <grpcpp/grpcpp.h>

#include "air_fanout.h"
#include "dtmf/v1/teleop.grpc.pb.h"

namespace dtmf::server {

// `entry` as the API streams it.
void fill_watch_response(v1::WatchAirResponse& out, const WatchEntry& entry);

// The watcher's options from `request`; throws std::invalid_argument naming the field out of range.
WatchOptions watch_options(const v1::WatchAirRequest& request);

}  // namespace dtmf::server
