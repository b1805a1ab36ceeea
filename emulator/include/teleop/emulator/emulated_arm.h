#pragma once
// An arm of CiA 402 torque drives, emulated: one teleop::drive drive per joint, each on its own
// CanBus endpoint, turning the joints of a MuJoCo arm in lock-step (drive::DriveGroup over
// ArmDrivePlants), with the drives' parameters made from what the master's configuration
// (`follower.canopen`, robot::CanopenHardwareConfig) says of each joint. What
// teleop_arm_emulator runs on SocketCAN and the tests on virtual buses.

#include <memory>
#include <vector>

#include "teleop/can/can_bus.h"
#include "teleop/drive/drive_group.h"
#include "teleop/drive/emulated_drive.h"
#include "teleop/emulator/arm_drive_plants.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_hardware.h"

namespace teleop::emulator {

/// The emulated drive of one joint, from the master's view of it (node, gear and its efficiency,
/// encoder, rated torque, largest torque): a DC servo motor of k_t = 0.1 N m/A whose rated current
/// makes the rated torque and whose peak current makes 1.25 x the joint's largest torque, a current
/// loop of about 1 kHz bandwidth, and a position loop for its holding quick stop that gives the
/// largest torque at 50 mrad, critically damped for the joint's inertia `joint_inertia_kgm2`.
drive::EmulatedDriveConfig arm_joint_drive(const robot::CanopenJointConfig& joint, double joint_inertia_kgm2);

/// The inertia each actuated joint of the arm sees at the arm's pose now (the joint-space mass
/// matrix's diagonal, the motors' armature included).
std::vector<double> joint_inertias(robot::MujocoHardware& arm);

class EmulatedArm {
 public:
  /// `arm` (without gravity compensation, stepped by `step_s`) and `buses` (joint k's drive on
  /// buses[k]) must outlive this. Throws std::invalid_argument for counts that differ and what
  /// the drives throw for their configuration.
  EmulatedArm(robot::MujocoHardware& arm, double step_s, const robot::CanopenHardwareConfig& config,
              const std::vector<can::CanBus*>& buses);

  /// Advances the drives and the arm by dt_s, in whole steps of the arm. Real-time safe.
  void step(double dt_s) { group_->step(dt_s); }
  drive::DriveGroup& drives() { return *group_; }
  const drive::DriveGroup& drives() const { return *group_; }
  const ArmDrivePlants& plant() const { return plant_; }
  ArmDrivePlants& plant() { return plant_; }

 private:
  ArmDrivePlants plant_;
  std::unique_ptr<drive::DriveGroup> group_;
};

}  // namespace teleop::emulator
