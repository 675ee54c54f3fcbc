#include "cmd_vel/log_cmd_vel.h"

#include <nlohmann/json.hpp>

#include "rows.h"

namespace dtmf::agent {

void LogCmdVel::publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) {
  const nlohmann::json line{{"t_ms", audio_ms},
                            {"stamp", store::iso_time(stamp)},
                            {"linear_mps", velocity.linear_mps},
                            {"angular_radps", velocity.angular_radps},
                            // The old name, kept for readers of the log for one release (until 0.2):
                            // "rps" read as revolutions per second; the value is rad/s.
                            {"angular_rps", velocity.angular_radps}};
  std::fprintf(out_, "%s\n", line.dump().c_str());
  std::fflush(out_);
}

}  // namespace dtmf::agent
