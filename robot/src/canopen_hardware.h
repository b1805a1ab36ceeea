#pragma once
// RobotHardware on an arm of CiA 402 torque drives (canopen_backend.h): one CanopenArmBus per CAN
// bus; read() takes the feedback that arrived, write() sends the joints' torques and the SYNC,
// hold() asks every drive for its quick stop, in which it brakes and holds by itself (the follower
// resumes it with its next write). Once one drive or bus has failed, every drive holds for good. Destroyed, it leaves the drives holding; when its heartbeat
// stops, they quick-stop by themselves anyway (0x6007).

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "canopen_arm_bus.h"
#include "teleop/can/can_bus.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/robot_hardware.h"

namespace teleop::robot {

/// The bus configuration of `interface`: its drives in the joints' order, the shared timing, a
/// SYNC every `sync_period_s` (for the load check, canopen_bus_load()).
CanopenBusConfig canopen_bus_config(const CanopenHardwareConfig& config, const std::string& interface,
                                    double sync_period_s);

class CanopenHardware final : public RobotHardware {
 public:
  using Clock = std::function<int64_t()>;  // monotonic [ns]

  /// On these buses (one per distinct `bus` of the joints, in the order they first appear):
  /// configures, enables and leaves the drives holding; `wait` paces the start-up (SDO answers,
  /// and the cycles of the walk: its pump, or the poll period slept). Throws naming what failed.
  /// `owned`: buses the hardware keeps alive (the SocketCAN interfaces it opened), if any.
  CanopenHardware(const CanopenHardwareConfig& config, double period_s, std::vector<can::CanBus*> buses,
                  const SdoWait& wait, Clock clock, std::vector<std::unique_ptr<can::CanBus>> owned = {});
  ~CanopenHardware() override;

  size_t joints() const override { return config_.joints.size(); }
  [[nodiscard]] HardwareStatus read(ArmState& state) override;
  [[nodiscard]] HardwareStatus write(const JointVector& tau_nm) override;
  [[nodiscard]] HardwareStatus hold() override;
  bool compensates_gravity() const override { return false; }
  HardwareLimits limits() const override;
  const char* name() const override { return name_.c_str(); }
  /// Commands clamped, cycles with feedback missing, EMCYs, frames refused, and the fault latched.
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override;

  /// The interfaces in the order the buses are given (one per distinct joint `bus`).
  static std::vector<std::string> interfaces(const CanopenHardwareConfig& config);

 private:
  struct Joint {
    size_t bus = 0;
    size_t axis = 0;  // index on its bus
  };
  void start(const SdoWait& wait);
  /// One start-up cycle: every bus's feedback in, `command` for each joint out, then the wait.
  template <typename Command>
  void start_cycle(const SdoWait& wait, Command command);
  void send_all();
  Cia402Axis& axis(const Joint& j) { return buses_[j.bus]->axis(j.axis); }

  CanopenHardwareConfig config_;
  std::vector<std::unique_ptr<can::CanBus>> owned_;
  Clock clock_;
  std::string name_;
  std::vector<std::unique_ptr<CanopenArmBus>> buses_;
  std::vector<Joint> joints_;
  unsigned cycle_ = 0;   // follower cycles, for the SYNC divider
  bool failed_ = false;  // a drive or a bus failed: every drive holds from then on
};

}  // namespace teleop::robot
