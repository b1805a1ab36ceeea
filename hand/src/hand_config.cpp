#include "teleop/hand/hand_config.h"

#include <algorithm>
#include <stdexcept>

#include "teleop/can/virtual_can_bus.h"
#include "teleop/common/joint_config.h"

namespace teleop::hand {

namespace {

// a list of exactly nine values (one per motor), or `fallback` for each when absent
HandMotorVector read_motor_list(const ConfigNode& s, const std::string& key, Range range, double fallback) {
  const JointVector v = read_joint_list(s, key, kHandMotors, range, fallback);
  HandMotorVector out{};
  std::copy_n(v.begin(), kHandMotors, out.begin());
  return out;
}

void read_gains(const ConfigNode& s, HandGains& g) {
  g.position_kp_a_per_rad = s.get_double("position_kp_a_per_rad", Range{0, 1e4}, g.position_kp_a_per_rad);
  g.position_ki_a_per_rad_s = s.get_double("position_ki_a_per_rad_s", Range{0, 1e6}, g.position_ki_a_per_rad_s);
  g.position_kd_a_s_per_rad = s.get_double("position_kd_a_s_per_rad", Range{0, 1e3}, g.position_kd_a_s_per_rad);
  g.position_integral_limit_a = s.get_double("position_integral_limit_a", Range{0, 100}, g.position_integral_limit_a);
  g.max_reference_velocity_radps =
      s.get_double("max_reference_velocity_radps", Range{1e-3, 100}, g.max_reference_velocity_radps);
  g.current_kp_v_per_a = s.get_double("current_kp_v_per_a", Range{0, 1e4}, g.current_kp_v_per_a);
  g.current_ki_v_per_a_s = s.get_double("current_ki_v_per_a_s", Range{0, 1e7}, g.current_ki_v_per_a_s);
}

void read_homing(const ConfigNode& s, HandHomingConfig& h) {
  h.enabled = s.get_bool("enabled", h.enabled);
  h.velocity_radps = s.get_double("velocity_radps", Range{1e-3, 10}, h.velocity_radps);
  h.current_threshold_a = s.get_double("current_threshold_a", Range{1e-3, 100}, h.current_threshold_a);
  h.timeout_s = s.get_double("timeout_s", Range{0.1, 120}, h.timeout_s);
  const HandMotorVector dir = read_motor_list(s, "direction", Range{-1, 1}, -1);
  for (size_t m = 0; m < kHandMotors; ++m) {
    if (dir[m] != 1.0 && dir[m] != -1.0) throw s.error("direction", "each entry must be -1 or 1");
    h.direction[m] = static_cast<int>(dir[m]);
  }
  h.stop_position_rad = read_motor_list(s, "stop_position_rad", Range{-10, 10}, -0.1);
}

void read_channels(const ConfigNode& s, HandAdapterConfig& a) {
  const auto ticks = read_motor_list(s, "ticks_per_rev", Range{1, 1e9}, 4096);
  const auto gear = read_motor_list(s, "gear_ratio", Range{1e-3, 1e5}, 100);
  const auto sign = read_motor_list(s, "sign", Range{-1, 1}, 1);
  const auto offset = read_motor_list(s, "offset_rad", Range{-10, 10}, 0);
  const auto rated = read_motor_list(s, "rated_current_a", Range{1e-3, 100}, 1);
  for (size_t m = 0; m < kHandMotors; ++m) {
    if (sign[m] != 1.0 && sign[m] != -1.0) throw s.error("sign", "each entry must be -1 or 1");
    a.channels[m] = {ticks[m], gear[m], static_cast<int>(sign[m]), offset[m], rated[m]};
  }
}

}  // namespace

HandNodeConfig parse_hand_config(const ConfigNode& root) {
  const ConfigNode s = root.child("hand");
  HandNodeConfig c;
  HandAdapterConfig& a = c.adapter;
  c.interface = s.get_string("interface");
  a.cycle_rate_hz = root.child("node").get_double("rate_hz", Range{1, 10000});
  a.bitrate_bps = s.get_double("bitrate_bps", Range{10e3, 1e6}, a.bitrate_bps);
  const auto ids = read_motor_list(s, "node_ids", Range{1, 127}, 0);
  for (size_t m = 0; m < kHandMotors; ++m) {
    a.node_ids[m] = ids[m] == 0 ? static_cast<can::NodeId>(m + 1) : static_cast<can::NodeId>(ids[m]);
  }
  read_channels(s, a);
  a.min_position_rad = read_motor_list(s, "min_position_rad", Range{-10, 10}, 0.0);
  a.max_position_rad = read_motor_list(s, "max_position_rad", Range{-10, 10}, 1.0);
  if (const auto g = s.optional_child("gains")) read_gains(*g, a.gains);
  a.default_current_limit_a = s.get_double("default_current_limit_a", Range{1e-3, 100}, a.default_current_limit_a);
  a.max_current_limit_a = s.get_double("max_current_limit_a", Range{1e-3, 100}, a.max_current_limit_a);
  a.heartbeat_ms = static_cast<uint16_t>(s.get_int("heartbeat_ms", Range{1, 10000}, a.heartbeat_ms));
  a.heartbeat_timeout_s = s.get_double("heartbeat_timeout_ms", Range{1, 60000}, 350) * 1e-3;
  a.boot_timeout_s = s.get_double("boot_timeout_ms", Range{1, 600000}, 2000) * 1e-3;
  a.sdo_timeout_s = s.get_double("sdo_timeout_ms", Range{1, 60000}, 200) * 1e-3;
  a.enable_timeout_s = s.get_double("enable_timeout_ms", Range{1, 60000}, 1000) * 1e-3;
  a.pdo_timeout_cycles = static_cast<uint32_t>(s.get_int("pdo_timeout_cycles", Range{1, 10000}, a.pdo_timeout_cycles));
  if (const auto h = s.optional_child("homing")) read_homing(*h, a.homing);
  c.command_timeout_s = s.get_double("command_timeout_ms", Range{1, 60000}, 100) * 1e-3;
  // what the adapter refuses (duplicate node ids, min >= max, ...) is a config error too
  try {
    can::VirtualCanBus bus(1);
    auto endpoint = bus.open();
    HandAdapter check(*endpoint, a);
  } catch (const std::invalid_argument& e) {
    throw root.error("hand", e.what());
  }
  return c;
}

}  // namespace teleop::hand
