#pragma once
// The collision reflex of a torque-controlled arm (as a Franka's: its collision thresholds):
// clamping each command to its limits does not bound the force a stiff command presses into a
// hard contact with, so the follower watches its own estimate of the external load, per joint
// and at the end effector, and when any crosses its threshold it stops moving into the contact:
// it holds where it is in compliant joint impedance and latches a fault (FAULT_CONTACT_REFLEX)
// until an operator resets it or a new command session starts.

#include <array>
#include <cstdint>

#include "teleop/common/joint_model.h"
#include "teleop/control/types.h"

namespace teleop::follower {

struct ContactReflexConfig {
  /// Off: no reflex (`contact_reflex: off` in YAML).
  bool enabled = true;
  /// |tau_ext| per joint above which the reflex trips [N*m]. Defaults: the Franka Panda's
  /// collision thresholds as its ROS driver sets them (franka_control, "upper nominal").
  JointVector joint_torque_nm = filled(20.0, {20.0, 20.0, 18.0, 18.0, 16.0, 14.0, 12.0});
  /// |F_ext| per axis of the base frame [N] and |M_ext| per axis [N*m], at the end effector.
  std::array<double, 3> force_n{20.0, 20.0, 20.0};
  std::array<double, 3> torque_nm{25.0, 25.0, 25.0};
  /// The compliant joint impedance the arm holds with once tripped.
  double hold_stiffness_nm_per_rad = 20.0;
  double hold_damping_nms_per_rad = 5.0;

  static JointVector filled(double rest, std::initializer_list<double> first);
};

/// What tripped the reflex, for the report.
enum class ReflexCause { kNone, kJointTorque, kForce, kTorque };

/// Real-time safe: check() neither allocates nor throws.
class ContactReflex {
 public:
  explicit ContactReflex(const ContactReflexConfig& config) : config_(config) {}

  /// Checks this cycle's external joint torque and end-effector wrench (force, moment; base
  /// frame). Returns true in the cycle the reflex trips; it then stays latched.
  bool check(const control::JointVector& tau_ext_nm, const control::Vector6& wrench);
  /// Clears the latch (an operator's reset, or a new command session).
  void reset() { latched_ = false; }

  bool latched() const { return latched_; }
  uint64_t trips() const { return trips_; }
  ReflexCause last_cause() const { return cause_; }
  /// The estimate that crossed its threshold at the last trip, as a multiple of that threshold.
  double last_trip_ratio() const { return trip_ratio_; }
  const ContactReflexConfig& config() const { return config_; }

 private:
  ReflexCause over_threshold(const control::JointVector& tau_ext_nm, const control::Vector6& wrench, double& ratio) const;

  ContactReflexConfig config_;
  bool latched_ = false;
  uint64_t trips_ = 0;
  ReflexCause cause_ = ReflexCause::kNone;
  double trip_ratio_ = 0.0;
};

const char* to_string(ReflexCause cause);

}  // namespace teleop::follower
