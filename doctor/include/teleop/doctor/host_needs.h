#pragma once
// What the node configs given to `teleop doctor` ask of this host: real-time scheduling, CAN
// buses at a bitrate, the DDS interfaces. Read with the nodes' own parsers, so the doctor judges
// exactly what the node would start with.

#include <string>
#include <vector>

#include "teleop/runtime/realtime.h"

namespace teleop::doctor {

struct RealtimeNeed {
  std::string node;                ///< the config's node name
  std::string file;
  runtime::RealtimeConfig realtime;
};

struct CanNeed {
  std::string interface;           ///< can0, vcan0
  double bitrate_bps = 0;          ///< what the config plans its bus load with
  std::string node;
  std::string file;
};

struct DdsNeed {
  std::string node;
  std::string file;
  std::vector<std::string> interface_whitelist;  ///< IPv4 addresses; empty: every interface
  bool multicast_discovery = true;
};

struct HostNeeds {
  std::vector<RealtimeNeed> realtime;
  std::vector<CanNeed> can;
  std::vector<DdsNeed> dds;

  /// The highest SCHED_FIFO priority a node asks for (0: none asks).
  int highest_priority() const;
  /// The priority the doctor judges: the highest asked for, else the nodes' default.
  int judged_priority() const;
  /// Whether some node fails at start without real-time (`realtime: required`).
  bool realtime_required() const;
};

/// Reads each node config (a file, or a name in config/nodes) and adds what it needs; a scenario
/// adds its nodes' configs. Throws ConfigError naming file, key and problem.
HostNeeds needs_of(const std::vector<std::string>& config_files);

}  // namespace teleop::doctor
