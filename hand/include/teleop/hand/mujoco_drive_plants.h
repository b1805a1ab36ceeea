#pragma once
// The MuJoCo hand (HandPlant) as the plant of the hand's nine emulated drives
// (teleop_hand_emulator --plant mujoco, docs/hand.md): channel k is motor k in SVH order. Each
// drive's motor torque at its gearbox output acts on the channel's main joint through the
// model's motor actuator (the coupled joints follow through the joint equalities); its encoder
// reads the simulated motor angle m = (q_main - q0) / f_main. So the model's joint limits are
// the drives' hard stops, and contacts stop the fingers.
//
// Timing: the model advances in its own timestep (1 ms); the drives' 50 us substeps apply their
// torques in between, and step() uses each channel's torque averaged over the step. Between
// two steps a channel reads the angle of the last step extrapolated by its velocity
// (first-order hold), so the drive's 2 kHz position loop sees a smooth encoder. A jammed channel
// (fault injection: stalled motor) holds its main joint where the jam found it.

#include <array>

#include "teleop/drive/drive_plant.h"
#include "teleop/drive/sampled_channel.h"
#include "teleop/hand/hand_plant.h"

namespace teleop::hand {

class MujocoDrivePlants final : public drive::SharedDrivePlant {
 public:
  /// Takes the hand; sets every motor actuator's torque limit to `torque_limit_nm` (> 0: the
  /// most the drives' motors can give at the gearbox output, so that MuJoCo never clamps a
  /// torque a drive makes) and reads the channels' state. Throws std::invalid_argument for a
  /// limit that is not positive.
  MujocoDrivePlants(HandPlant hand, double torque_limit_nm);

  size_t channels() const override { return kHandMotors; }
  drive::DrivePlant& channel(size_t k) override { return channels_[k]; }
  double step_s() const override;
  void step() override;

  /// The simulated hand, for observation (joint angles, contacts) and setup.
  HandPlant& hand() { return hand_; }
  const HandPlant& hand() const { return hand_; }
  /// Each channel's torque of the last step [N m] (averaged over it, before MuJoCo's clamp).
  const HandMotorVector& last_torque_nm() const { return last_torque_nm_; }

  /// Reads the channels' state from the model again (after the owner moved the model, e.g.
  /// reset it to a keyframe).
  void sync_from_model();

 private:
  class Channel final : public drive::SampledChannel {
   private:
    friend class MujocoDrivePlants;
    bool was_jammed_ = false;
    double jam_rad_ = 0.0;  // where the main joint is held while jammed
  };

  HandPlant hand_;
  std::array<Channel, kHandMotors> channels_{};
  HandMotorVector last_torque_nm_{};
};

}  // namespace teleop::hand
