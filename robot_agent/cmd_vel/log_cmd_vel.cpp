#include "cmd_vel/log_cmd_vel.h"

#include <nlohmann/json.hpp>

#include "rows.h"

namespace dtmf::agent {

void LogCmdVel::publish(const Velocity& velocity, double audio_ms, std::chrono::system_clock::time_point stamp) {
  const nlohmann::json line{{"t_ms", audio_ms},
                            {"stamp", store::iso_time(stamp)},
                            {"linear_mps", velocity.linear_mps},
                            {"angular_rps", velocity.angular_rps}};
  std::fprintf(out_, "%s\n", line.dump().c_str());
  std::fflush(out_);
}

}  // namespace dtmf::agent
