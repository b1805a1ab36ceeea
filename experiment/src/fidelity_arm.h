#pragma once
// One arm of the fidelity study (fidelity_study.h): a MuJoCo plant, nominal (the twin) or
// perturbed with noisy sensors (the "real" robot), driven by one of control/'s controllers, which
// always computes on the nominal model (the controller's own model of the robot, as a real
// robot's controller has). step() is one lock-step: the controller's step on the last
// measurement, then one model timestep.

#include <memory>
#include <optional>
#include <vector>

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/controllers.h"
#include "teleop/experiment/fidelity_study.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/sim/mujoco_model.h"
#include "teleop/sim/plant_perturbation.h"

namespace teleop::experiment {

class FidelityArm {
 public:
  /// `real_seed`: the perturbed robot and its sensor noise of that seed; none: the nominal twin.
  /// Loads the model twice (plant, controller). Throws std::runtime_error naming the model when it
  /// does not have exactly the arm's 7 joints or lacks the end-effector site.
  FidelityArm(const FidelityStudyConfig& config, const std::string& model_path, FidelityController controller,
              std::optional<uint64_t> real_seed);

  /// Puts the arm at rest at `q_rad` and measures it (setup).
  void place(const control::JointVector& q_rad);
  /// One lock-step: the controller's torque for `command` on the last measurement, applied for one
  /// model timestep, then the new measurement. Real-time safe.
  void step(const RecordedCommand& command);
  /// The same with a whole command (the Cartesian controller's pose and twist). Real-time safe.
  void step(const control::ArmCommand& command);
  /// The controller's torque of the last step (before the motors' limits).
  const control::JointVector& tau_commanded() const { return tau_commanded_; }
  /// The plant (its contacts of the last step: the true external forces).
  const sim::MujocoModel& plant() const { return plant_; }
  /// The arm's joints in the plant.
  const sim::ActuatedJoints& joints() const { return joints_; }

  /// The measured joint state (after the last step; noisy on the real robot).
  const control::ArmState& measured() const { return measured_; }
  /// The measured link-side joint torque of the last step: the motor torque plus the joint's
  /// friction and damping (what a torque sensor behind the gear sees), noisy on the real robot.
  const control::JointVector& tau_measured() const { return tau_; }
  /// Whether the last step had a contact.
  bool in_contact() const { return plant_.data()->ncon > 0; }
  double timestep_s() const { return plant_.model()->opt.timestep; }
  int mujoco_warnings() const;
  const sim::AppliedPerturbation& perturbation() const { return perturbation_; }

 private:
  void measure();

  sim::MujocoModel plant_;
  sim::MujocoModel nominal_;
  sim::ActuatedJoints joints_;
  control::ArmDynamics dynamics_;
  std::unique_ptr<control::Controller> controller_;
  std::optional<sim::SensorNoise> noise_;
  sim::AppliedPerturbation perturbation_;
  std::vector<int> joint_of_dof_;  // the arm joint of each degree of freedom, -1 for others
  control::ArmState measured_;
  control::ArmCommand command_;
  control::JointVector tau_ = control::JointVector::Zero();
  control::JointVector tau_commanded_ = control::JointVector::Zero();
};

/// The end-effector pose by the nominal model's forward kinematics (what a robot reports from its
/// measured joints), on an mjData of its own.
class ForwardKinematics {
 public:
  ForwardKinematics(const std::string& model_path, const std::string& ee_site);
  /// Position [m] and unit quaternion (w, x, y, z) of the site at `q_rad`.
  void pose(const control::JointVector& q_rad, std::array<double, 3>& position_m, Quaternion& rotation);

 private:
  sim::MujocoModel model_;
  sim::ActuatedJoints joints_;
  int site_;
};

}  // namespace teleop::experiment
