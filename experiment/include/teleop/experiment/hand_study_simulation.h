#pragma once
// One run of the SVH hand study as a simulation stepped one control cycle at a time: the scene
// with the run's link inertias, the minimum-jerk path through the study's keyframes, the arm's
// PD with gravity compensation and the hand's PD per motor channel (docs/hand.md).
// run_hand_study_case() samples it; bench/hand_model_bench.cpp times its step.

#include <array>
#include <vector>

#include "teleop/experiment/hand_study.h"
#include "teleop/hand/hand_plant.h"
#include "teleop/control/min_jerk.h"
#include "teleop/hand/position_control.h"

namespace teleop::experiment {

class HandStudySimulation {
 public:
  /// The arm joints the study drives (the paper's names), in the order of its poses.
  static constexpr std::array<const char*, 6> kArmJointNames = {
      "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"};

  /// Loads the scene, applies the run's settings, designs every PD at the path's last keyframe
  /// and starts at its first. Throws std::runtime_error naming the model when a keyframe or joint
  /// is missing or a keyframe puts a motor outside its range.
  HandStudySimulation(const HandStudyConfig& config, const HandStudyRun& run);

  /// One control cycle: the path's references now, the arm's and the hand's torques, one model
  /// timestep. Real-time safe.
  void step();

  /// Time since the start of the path [s].
  double time_s() const;
  /// When the path ends and the hand holds the last keyframe [s].
  double motion_s() const { return path_.duration_s(); }
  /// Whether the last step's contacts held one other than the index fingertip on the panel.
  bool foreign_contact() const;

  hand::HandPlant& plant() { return plant_; }
  const hand::HandPlant& plant() const { return plant_; }

 private:
  struct ArmJoint {
    int qpos = 0;
    int dof = 0;
    int actuator = 0;
    hand::PdGains gains;
  };

  hand::HandPlant plant_;
  control::MinJerkPath path_;
  // designed with the plant at the path's last keyframe (the constructor puts it there first)
  std::array<ArmJoint, kArmJointNames.size()> arm_;
  hand::HandPositionControl hand_control_;
  int tip_geom_;
  int panel_geom_;
  long steps_ = 0;
  // the references of the cycle: the arm's joints, then the motors
  std::vector<double> ref_;
  std::vector<double> dref_;
  hand::HandMotorVector m_ref_{};
  hand::HandMotorVector dm_ref_{};
};

}  // namespace teleop::experiment
