#pragma once
// The reflexes of a torque-controlled arm (as a Franka's collision thresholds and velocity
// limits). Clamping each command to its limits bounds neither the force a stiff command presses
// into a hard contact with nor the speed at which a badly tuned one swings the arm into
// something, so the follower watches its own estimate of the external load, per joint and at the
// flange, and its joint speeds; when any crosses its threshold it stops moving: it holds where it
// is in compliant joint impedance and latches a fault (FAULT_CONTACT_REFLEX for a load,
// FAULT_SPEED_REFLEX for a speed) until an operator resets it or a new command session starts.

#include <array>
#include <cstdint>
#include <initializer_list>

#include "teleop/common/joint_model.h"
#include "teleop/control/types.h"

namespace teleop::follower {

struct SafetyReflexConfig {
  /// Off: no reflex (`reflex: off` in YAML).
  bool enabled = true;
  /// |tau_ext| per joint above which the reflex trips [N*m]. Defaults: the Franka Panda's
  /// collision thresholds as its ROS driver sets them (franka_control, "upper nominal").
  JointVector joint_torque_nm = filled(20.0, {20.0, 20.0, 18.0, 18.0, 16.0, 14.0, 12.0});
  /// |F_ext| per axis of the base frame [N] and |M_ext| per axis [N*m], at the flange.
  std::array<double, 3> force_n{20.0, 20.0, 20.0};
  std::array<double, 3> torque_nm{25.0, 25.0, 25.0};
  /// |dq| per joint [rad/s]. Defaults: the Panda's joint velocity limits (data sheet).
  JointVector joint_velocity_radps = filled(2.61, {2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61});
  /// The compliant joint impedance the arm holds with once tripped.
  double hold_stiffness_nm_per_rad = 20.0;
  double hold_damping_nms_per_rad = 5.0;
  /// After a joint-speed trip the arm is braked to a stop, not left to coast in the compliant
  /// hold (measured: a huge-gain command's limit cycle tripped at 2.5 rad/s towards the wall, and
  /// the compliant hold let it hit the wall with up to 1.8 kN): the brake takes this share of the
  /// arm's velocity per cycle, tau = -(share / cycle) M(q) dq (speed_brake.h), within the torque
  /// limits.
  double brake_share_per_cycle = 0.2;

  static JointVector filled(double rest, std::initializer_list<double> first);
};

/// What tripped the reflex.
enum class ReflexCause { kNone, kJointTorque, kForce, kTorque, kJointVelocity };

/// Real-time safe: check() neither allocates nor throws.
class SafetyReflex {
 public:
  explicit SafetyReflex(const SafetyReflexConfig& config) : config_(config) {}

  /// Checks this cycle's external joint torque, flange wrench (force, moment; base frame) and
  /// joint velocities. Returns true in the cycle the reflex trips; it then stays latched.
  bool check(const control::JointVector& tau_ext_nm, const control::Vector6& wrench, const control::JointVector& dq_radps);
  /// Clears the latch (an operator's reset, or a new command session).
  void reset() { latched_ = false; }

  bool latched() const { return latched_; }
  uint64_t trips() const { return trips_; }
  ReflexCause last_cause() const { return cause_; }
  /// The fault the latched reflex reports (msg::FAULT_CONTACT_REFLEX or FAULT_SPEED_REFLEX).
  uint32_t fault_code() const;
  /// The quantity that crossed its threshold at the last trip, as a multiple of that threshold.
  double last_trip_ratio() const { return trip_ratio_; }
  /// The largest quantity of the last check as a multiple of its threshold, and the largest seen
  /// so far (how close a run came).
  double ratio() const { return ratio_; }
  double peak_ratio() const { return peak_ratio_; }
  const SafetyReflexConfig& config() const { return config_; }

 private:
  /// The quantity closest to (or furthest over) its threshold, as the ratio of the two.
  ReflexCause largest(const control::JointVector& tau_ext_nm, const control::Vector6& wrench,
                      const control::JointVector& dq_radps, double& ratio) const;

  SafetyReflexConfig config_;
  bool latched_ = false;
  uint64_t trips_ = 0;
  ReflexCause cause_ = ReflexCause::kNone;
  double trip_ratio_ = 0.0;
  double ratio_ = 0.0;
  double peak_ratio_ = 0.0;
};

const char* to_string(ReflexCause cause);

}  // namespace teleop::follower
