#pragma once
// The twin's MuJoCo simulation: the robot model plus the safety-margin geometry only the twin sees,
// driven either by the joint PD coupling of PARTI eq. 2 (tau = K (q_coupled - q) - D dq, never by
// writing positions, so contacts and joint limits act on it) or by joint torques (lock-step and
// hardware-in-the-loop controllers), always on top of the compensation of MuJoCo's bias forces
// (gravity, Coriolis) on the driven joints. After each step it holds the constraint torque on the
// driven joints (eq. 1/3: qfrc_constraint, joint friction rows left out unless configured).
//
// Construction loads and allocates (throws std::runtime_error naming the file); reset(), the
// steps, set_state() and the getters do not allocate.

#include <vector>

#include "teleop/common/joint_model.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/sim/model_additions.h"
#include "teleop/sim/mujoco_model.h"
#include "teleop/twin/pair_observer.h"
#include "teleop/twin/twin_model_config.h"

namespace teleop::twin {

/// The MJCF elements of the configured margins: spheres on their bodies, planes in the world.
/// They collide only with each other (collision bit 16), frictionless, and add no mass.
std::vector<sim::ModelAddition> margin_geometry(const TwinModelConfig& config);

class TwinSimulation {
 public:
  explicit TwinSimulation(const TwinModelConfig& config);

  /// Back to the configured keyframe (or the default state).
  void reset();
  /// One control period coupled to `q_coupled_rad` by eq. 2. Real-time safe.
  void step_coupled(const JointVector& q_coupled_rad);
  /// One control period with `tau_nm` on the driven joints. Real-time safe.
  void step_torque(const JointVector& tau_nm);
  /// The same plus -damping * dq, integrated implicitly (as joint damping: stable for stiff
  /// gains on light links where an explicit damping torque is not). Real-time safe.
  void step_torque(const JointVector& tau_nm, const JointVector& damping_nms_per_rad);
  /// Hardware in the loop: the driven joints take the measured state, everything derived is
  /// recomputed (mj_forward), nothing is integrated. Real-time safe.
  void set_state(const JointVector& q_rad, const JointVector& dq_radps);

  /// Puts a geom at `pos_m` in its body's frame (mjModel::geom_pos); the next step sees it there.
  /// Between steps only. Real-time safe.
  void set_geom_position(int geom, const std::array<double, 3>& pos_m);

  size_t joints() const { return joints_.count; }
  const JointVector& q_rad() const { return q_; }
  const JointVector& dq_radps() const { return dq_; }
  /// Torque the twin's joints applied in the last period (coupling or command), bias compensation excluded.
  const JointVector& tau_nm() const { return tau_; }
  /// Constraint torque on the driven joints from the last step (what eq. 3 renders).
  const JointVector& constraint_torque_nm() const { return constraint_; }
  double time_s() const { return sim_.data()->time; }
  /// MuJoCo warnings raised so far (instability, contact or constraint buffers full, ...): any
  /// is a fault of the run.
  int warnings() const {
    int n = 0;
    for (const mjWarningStat& w : sim_.data()->warning) n += w.number;
    return n;
  }
  int substeps() const { return substeps_; }

  const PairObserver& contact_pairs() const { return contacts_; }
  const PairObserver& distance_pairs() const { return distances_; }
  Wrench contact_wrench(size_t pair) const { return contacts_.contact_wrench(sim_.model(), sim_.data(), pair); }
  int contact_count(size_t pair) const { return contacts_.contact_count(sim_.data(), pair); }
  double distance_m(size_t pair) const { return distances_.distance(sim_.model(), sim_.data(), pair, config_.distance_range_m); }

  const TwinModelConfig& config() const { return config_; }
  const sim::MujocoModel& simulation() const { return sim_; }
  sim::MujocoModel& simulation() { return sim_; }

 private:
  template <typename TorqueLaw>
  void advance(TorqueLaw&& law);
  void read_back();
  void set_joint_damping(const JointVector& damping_nms_per_rad);
  void apply_geom_offsets();

  TwinModelConfig config_;
  sim::MujocoModel sim_;
  sim::ActuatedJoints joints_;
  PairObserver contacts_;
  PairObserver distances_;
  int substeps_ = 1;
  JointVector q_{};
  JointVector dq_{};
  JointVector tau_{};
  JointVector constraint_{};
  JointVector model_damping_{};
  // constraint forces with the joint-friction rows zeroed, and their joint torque
  std::vector<mjtNum> efc_rendered_;
  std::vector<mjtNum> qfrc_rendered_;
};

}  // namespace teleop::twin
