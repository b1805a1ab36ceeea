#pragma once
// The operator's input device behind an interface: a torque-controlled arm used as master that
// reports its joint state and renders feedback torques. The leader's node sees only this; which
// device it drives is chosen in the configuration (`leader.device`) from a DeviceRegistry
// (device_registry.h). Implementations: the script itself, a simulated haptic arm pulled by a
// simulated operator, the replay of a recording (simulated_devices.h); a 6-DoF mouse and a gamepad
// through Linux input (input_devices.h); a real device plugs in here.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "teleop/common/joint_model.h"

namespace teleop::leader {

struct DeviceState {
  JointVector q_rad{};
  JointVector dq_radps{};
  /// The torque the operator applies to the device, where known (simulation), else 0.
  JointVector tau_operator_nm{};
  /// Bit k set: the device's button k is pressed (leader.buttons says what a button does).
  uint32_t buttons = 0;
  /// A Cartesian device's handle (a 6-DoF mouse, a gamepad: DeviceSpec::cartesian()), in the
  /// follower's base frame about where it started: position, orientation and twist (linear, then
  /// angular). It leaves the joints above as the leader set them (its home, at rest); a joint
  /// device leaves these, and its flange pose comes from the arm's model.
  std::array<double, 3> position_m{};
  std::array<double, 4> orientation_wxyz{1.0, 0.0, 0.0, 0.0};
  std::array<double, 6> twist{};
};

/// What the simulated operator (leader.motion) wants this period: where the device should be, in
/// the script's joint space (about leader.home_rad), and the torque the operator adds on purpose.
struct OperatorIntent {
  JointVector q_rad{};
  JointVector dq_radps{};
  JointVector tau_nm{};
  /// The operator's hand is on the device (leader.let_go_at_s: not from then on).
  bool hand_on = true;
};

class LeaderDevice {
 public:
  virtual ~LeaderDevice() = default;
  virtual size_t joints() const = 0;
  /// The simulated operator's intent for the coming period, given before read(). A simulated
  /// device moves by it; a real device, held by a real operator, ignores it (the default).
  /// Real-time safe.
  virtual void set_operator_intent(const OperatorIntent& intent) { (void)intent; }
  /// Real-time safe. False when the device cannot be read.
  [[nodiscard]] virtual bool read(DeviceState& state) = 0;
  /// Renders `feedback_nm` for the next period. Real-time safe. False when refused.
  [[nodiscard]] virtual bool write(const JointVector& feedback_nm) = 0;
  virtual const char* name() const = 0;
  /// Adds the device's own counters (reads refused, efforts clamped) to the leader's report.
  /// After the loop.
  virtual void report_counters(std::vector<std::pair<std::string, double>>& counters) const { (void)counters; }
};

}  // namespace teleop::leader
