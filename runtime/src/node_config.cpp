#include "teleop/runtime/node_config.h"

#include <algorithm>

namespace teleop::runtime {

NodeConfig parse_node_config(const ConfigNode& section, const std::string& default_name) {
  NodeConfig c;
  c.name = section.get_string("name", default_name);
  if (c.name.empty() || c.name.size() > 31) throw section.error("name", "must have 1 to 31 characters");
  c.rate_hz = section.get_double("rate_hz", Range{1, 10'000}, 1000.0);
  c.status_rate_hz = section.get_double("status_rate_hz", Range{0.1, 100}, 10.0);
  if (c.status_rate_hz > c.rate_hz) throw section.error("status_rate_hz", "must not exceed rate_hz");
  c.duration_s = section.get_double("duration_s", Range{0, 1e6}, 0.0);
  c.max_catch_up_cycles = static_cast<uint64_t>(section.get_int("max_catch_up_cycles", Range{0, 100'000}, 10));
  const std::string mode = section.get_choice("realtime", {"off", "optional", "required"}, "off");
  c.realtime.mode = mode == "required" ? RealtimeMode::kRequired
                    : mode == "optional" ? RealtimeMode::kOptional
                                         : RealtimeMode::kOff;
  c.realtime.priority = static_cast<int>(section.get_int("realtime_priority", Range{1, 99}, 80));
  // the middleware's threads: real-time below the loop (0: SCHED_OTHER)
  c.realtime.dds_priority =
      static_cast<int>(section.get_int("dds_priority", Range{0, 98}, std::max(0, c.realtime.priority - 10)));
  if (c.realtime.dds_priority >= c.realtime.priority) {
    throw section.error("dds_priority", "must be below realtime_priority: nothing may run before the loop");
  }
  c.probes = section.get_string_list("probes");
  return c;
}

}  // namespace teleop::runtime
