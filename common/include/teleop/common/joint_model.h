#pragma once
// A simple simulated joint space: independent joints with inertia and viscous friction, and a
// stiff virtual wall on one joint. It stands in for a robot until the MuJoCo models take over,
// and gives the nodes real dynamics (and a real contact torque) to exchange.

#include <array>
#include <cstddef>

namespace teleop {

constexpr size_t kMaxJoints = 32;
using JointVector = std::array<double, kMaxJoints>;

struct JointModelParams {
  size_t joints = 7;
  double inertia_kgm2 = 0.2;
  double viscous_nms_per_rad = 0.5;
  /// Joint `wall_joint` meets a wall at this angle (from below); a huge value disables it.
  size_t wall_joint = 0;
  double wall_q_rad = 1e9;
  double wall_stiffness_nm_per_rad = 2000.0;
};

/// Integrates tau = I ddq + b dq + tau_contact per joint with semi-implicit Euler.
/// Real-time safe: fixed-size storage only.
class JointModel {
 public:
  explicit JointModel(const JointModelParams& params);

  /// Sets the state (e.g. the home pose); velocities zero.
  void reset(const JointVector& q_rad);
  /// Advances by dt under the applied joint torques.
  void step(const JointVector& tau_nm, double dt_s);

  size_t joints() const { return params_.joints; }
  const JointVector& q() const { return q_; }
  const JointVector& dq() const { return dq_; }
  /// Torque the wall exerts on each joint at the current state (<= 0 on the wall joint, else 0).
  const JointVector& contact_torque() const { return contact_; }

 private:
  void update_contact();

  JointModelParams params_;
  JointVector q_{};
  JointVector dq_{};
  JointVector contact_{};
};

}  // namespace teleop
