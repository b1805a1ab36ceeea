#include "teleop/robot/canopen_backend.h"

#include <algorithm>
#include <cmath>

#include "canopen_hardware.h"
#include "teleop/can/socketcan_bus.h"
#include "teleop/common/clock.h"

namespace teleop::robot {
namespace {

// one drive, as its mapping in `canopen.drives` says
CanopenJointConfig parse_drive(const ConfigNode& d) {
  CanopenJointConfig j;
  j.bus = d.get_string("bus");
  if (j.bus.empty()) throw d.error("bus", "names the drive's SocketCAN interface (can0)");
  j.node = static_cast<uint8_t>(d.get_int("node", {1, 127}));
  Cia402AxisConfig& a = j.axis;
  a.gear_ratio = d.get_double("gear_ratio", {1e-3, 1e5});
  a.gear_efficiency = d.get_double("gear_efficiency", {0.05, 1.0}, 1.0);
  a.encoder_ticks_per_rev = d.get_double("encoder_ticks_per_rev", {1, 1e9});
  a.rated_torque_nm = d.get_double("rated_torque_mnm", {1, 1e7}) * 1e-3;
  a.offset_rad = d.get_double("offset_rad", {-100, 100}, 0.0);
  a.inverted = d.get_bool("inverted", false);
  a.max_torque_nm = d.get_double("max_torque_nm", {1e-3, 1e5});
  a.velocity_filter_hz = d.get_double("velocity_filter_hz", {1, 1e4}, a.velocity_filter_hz);
  j.q_min_rad = d.get_double("q_min_rad", {-1e3, 1e3}, j.q_min_rad);
  j.q_max_rad = d.get_double("q_max_rad", {-1e3, 1e3}, j.q_max_rad);
  if (j.q_min_rad >= j.q_max_rad) throw d.error("q_max_rad", "must be above q_min_rad");
  return j;
}

uint16_t milliseconds(const ConfigNode& c, const std::string& key, uint16_t fallback) {
  return static_cast<uint16_t>(c.get_int(key, {1, 60000}, fallback));
}

}  // namespace

std::unique_ptr<RobotHardware> CanopenHardwareSpec::make(double period_s) const {
  std::vector<std::unique_ptr<can::CanBus>> owned;
  std::vector<can::CanBus*> buses;
  for (const std::string& interface : CanopenHardware::interfaces(config_)) {
    owned.push_back(std::make_unique<can::SocketCanBus>(interface));
    buses.push_back(owned.back().get());
  }
  SdoWait wait;
  wait.poll = std::chrono::nanoseconds(static_cast<int64_t>(period_s * 1e9));
  wait.timeout = std::chrono::nanoseconds(static_cast<int64_t>(config_.sdo_timeout_s * 1e9));
  return std::make_unique<CanopenHardware>(config_, period_s, std::move(buses), wait, [] { return monotonic_now_ns(); },
                                           std::move(owned));
}

std::shared_ptr<const CanopenHardwareSpec> parse_canopen_hardware(const ConfigNode& section) {
  const ConfigNode c = section.child("canopen");
  CanopenHardwareConfig config;
  for (const ConfigNode& d : c.get_node_list("drives")) config.joints.push_back(parse_drive(d));
  if (config.joints.empty()) throw c.error("drives", "lists the joints' drives, in the follower's joint order");
  if (config.joints.size() > kMaxJoints) throw c.error("drives", "lists more than " + std::to_string(kMaxJoints));
  for (size_t i = 0; i < config.joints.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (config.joints[k].bus == config.joints[i].bus && config.joints[k].node == config.joints[i].node) {
        throw c.error("drives", "gives node " + std::to_string(config.joints[i].node) + " on " + config.joints[i].bus +
                                    " to joints " + std::to_string(k + 1) + " and " + std::to_string(i + 1));
      }
    }
  }
  config.master_node = static_cast<uint8_t>(c.get_int("master_node", {1, 127}, config.master_node));
  config.master_heartbeat_ms = milliseconds(c, "master_heartbeat_ms", config.master_heartbeat_ms);
  config.drive_heartbeat_ms = milliseconds(c, "drive_heartbeat_ms", config.drive_heartbeat_ms);
  config.master_lost_after_ms = milliseconds(c, "master_lost_after_ms", config.master_lost_after_ms);
  config.drive_lost_after_ms = milliseconds(c, "drive_lost_after_ms", config.drive_lost_after_ms);
  if (config.master_lost_after_ms <= config.master_heartbeat_ms) {
    throw c.error("master_lost_after_ms", "must be above master_heartbeat_ms");
  }
  if (config.drive_lost_after_ms <= config.drive_heartbeat_ms) {
    throw c.error("drive_lost_after_ms", "must be above drive_heartbeat_ms");
  }
  config.bitrate_bps = c.get_double("bitrate", {1e4, 1e6}, config.bitrate_bps);
  config.sync_divider = static_cast<unsigned>(c.get_int("sync_divider", {1, 100}, config.sync_divider));
  config.state_timeout_s = c.get_double("state_timeout_ms", {0.5, 1000}, config.state_timeout_s * 1e3) * 1e-3;
  config.sdo_timeout_s = c.get_double("sdo_timeout_ms", {1, 10000}, config.sdo_timeout_s * 1e3) * 1e-3;
  config.enable_timeout_s = c.get_double("enable_timeout_s", {0.01, 60}, config.enable_timeout_s);
  return std::make_shared<const CanopenHardwareSpec>(config);
}

void add_canopen_backend(HardwareRegistry& registry) {
  registry.add("canopen", [](const ConfigNode& section) { return parse_canopen_hardware(section); });
}

}  // namespace teleop::robot
