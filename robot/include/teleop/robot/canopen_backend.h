#pragma once
// An arm of CiA 402 drives on SocketCAN as a hardware backend (`hardware: canopen`): one drive per
// joint in cyclic synchronous torque (mode 10), on one or more CAN buses, configured by SDO at
// start from the section's `canopen:` keys, one YAML mapping per drive (docs/robots.md). The
// follower's torque goes to the drives every SYNC; a drive's fault, a lost heartbeat, a reboot or
// bus-off is a hardware fault; the drives quick-stop by themselves when the follower dies (0x6007).

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/robot/cia402_axis.h"
#include "teleop/robot/hardware_registry.h"

namespace teleop::robot {

/// One joint: the drive that turns it, where it is, what it is.
struct CanopenJointConfig {
  std::string bus;  // the SocketCAN interface ("can0")
  uint8_t node = 0;
  Cia402AxisConfig axis;
  double q_min_rad = -std::numeric_limits<double>::infinity();
  double q_max_rad = std::numeric_limits<double>::infinity();
};

struct CanopenHardwareConfig {
  std::vector<CanopenJointConfig> joints;  // the follower's joint order
  uint8_t master_node = 127;
  uint16_t master_heartbeat_ms = 10;
  uint16_t drive_heartbeat_ms = 10;
  uint16_t master_lost_after_ms = 50;  // the drives quick-stop this long after the master's last heartbeat
  uint16_t drive_lost_after_ms = 50;   // a drive silent this long is a fault
  double bitrate_bps = 1e6;            // for the load check (the interface's own is set with ip link)
  /// A SYNC every this many follower cycles: the bus's rate is the follower's / sync_divider.
  unsigned sync_divider = 1;
  /// Feedback older than this (since its SYNC) is stale: the drives hold by their quick stop.
  double state_timeout_s = 0.005;
  double sdo_timeout_s = 0.2;
  /// The walk to enabled and into the holding quick stop at start, at most this long.
  double enable_timeout_s = 1.0;
};

class CanopenHardwareSpec final : public HardwareSpec {
 public:
  explicit CanopenHardwareSpec(CanopenHardwareConfig config) : config_(std::move(config)) {}
  const char* backend() const override { return "canopen"; }
  /// Opens the buses, configures and enables the drives, and leaves them holding (quick stop)
  /// until the follower's first command. Throws naming the interface, the drive or the object.
  std::unique_ptr<RobotHardware> make(double period_s) const override;
  const CanopenHardwareConfig& config() const { return config_; }

 private:
  CanopenHardwareConfig config_;
};

/// Reads `section.canopen` (throws ConfigError naming the key).
std::shared_ptr<const CanopenHardwareSpec> parse_canopen_hardware(const ConfigNode& section);

/// Registers the arm of CiA 402 drives as `canopen`.
void add_canopen_backend(HardwareRegistry& registry);

}  // namespace teleop::robot
