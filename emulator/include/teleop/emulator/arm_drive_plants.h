#pragma once
// The arm of a MuJoCo scene as the plant of emulated joint drives (drive::SharedDrivePlant): one
// channel per joint, each drive's torque averaged over a step and written to the arm, the joints'
// angles and rates read back, held and extrapolated by their rate between two steps. The arm must
// not compensate its own gravity (robot::MujocoHardwareConfig::gravity_compensated = false): the
// drives carry its weight, as real servo drives do. A channel sees its joint through an absolute
// encoder at `offset_rad` (the joint angle it reads 0 at), turned the other way when `inverted`,
// as the master's configuration says of the joint. A jammed channel (the drive's holding brake
// engaged, or a stall injected) holds its joint where it engaged, at rest, whatever the others do.
// Real-time safe after construction.

#include <array>
#include <vector>

#include "teleop/drive/drive_plant.h"
#include "teleop/drive/sampled_channel.h"
#include "teleop/robot/mujoco_hardware.h"

namespace teleop::emulator {

/// How a drive's encoder and motor see its joint.
struct JointMounting {
  double offset_rad = 0.0;
  bool inverted = false;
};

class ArmDrivePlants final : public drive::SharedDrivePlant {
 public:
  /// `arm` (which must outlive this) advances one step per write(), of `step_s`; one mounting
  /// per joint of the arm. Throws std::invalid_argument when the counts differ.
  ArmDrivePlants(robot::MujocoHardware& arm, double step_s, const std::vector<JointMounting>& mountings);

  size_t channels() const override { return channels_.size(); }
  drive::DrivePlant& channel(size_t k) override { return channels_[k]; }
  double step_s() const override { return step_s_; }
  void step() override;

  /// A torque on the joints from outside the drives (an operator's hand on an arm used as a
  /// haptic master), added to theirs at every step from the next on. Real-time safe.
  void set_external_torque(const JointVector& tau_nm) { external_nm_ = tau_nm; }
  /// The arm's state after the last step, as the simulation has it (joint side).
  const robot::ArmState& state() const { return state_; }
  /// Steps whose write the arm refused (a non-finite torque).
  uint64_t refused_steps() const { return refused_; }

 private:
  class Channel final : public drive::SampledChannel {
   private:
    friend class ArmDrivePlants;
    JointMounting mounting_;
    bool held_ = false;        // jammed at the last step
    double held_q_rad_ = 0.0;  // the joint's angle where it was jammed (joint side)
  };
  void take_state();

  robot::MujocoHardware& arm_;
  double step_s_;
  std::vector<Channel> channels_;
  robot::ArmState state_;
  JointVector torque_nm_{};
  JointVector external_nm_{};
  JointVector held_q_rad_{};  // the braked joints' angles, placed together after each step
  std::array<bool, kMaxJoints> held_{};
  uint64_t refused_ = 0;
};

}  // namespace teleop::emulator
