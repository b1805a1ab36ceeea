#pragma once
// The `scripted` device: exactly where the simulated operator wants it (leader.motion), with no
// dynamics of its own. It renders nothing; the feedback is still computed and traced.

#include <memory>

#include "teleop/leader/device_registry.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

class ScriptedDevice final : public LeaderDevice {
 public:
  explicit ScriptedDevice(size_t joints) : joints_(joints) {}

  size_t joints() const override { return joints_; }
  /// Real-time safe.
  void set_operator_intent(const OperatorIntent& intent) override {
    q_rad_ = intent.q_rad;
    dq_radps_ = intent.dq_radps;
  }
  /// The intent, as given; no operator torque (there is nothing to push). Real-time safe.
  [[nodiscard]] bool read(DeviceState& state) override {
    state.q_rad = q_rad_;
    state.dq_radps = dq_radps_;
    state.tau_operator_nm.fill(0.0);
    return true;
  }
  /// Accepts and drops the feedback: a script cannot be pushed back. Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override {
    (void)feedback_nm;
    return true;
  }
  const char* name() const override { return "scripted"; }

 private:
  size_t joints_;
  JointVector q_rad_{};
  JointVector dq_radps_{};
};

/// The scripted device's settings (it has none): the default of a leader's configuration.
std::shared_ptr<const DeviceSpec> scripted_device_spec();

}  // namespace teleop::leader
