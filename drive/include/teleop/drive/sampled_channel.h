#pragma once
// One channel of a SharedDrivePlant (drive_plant.h) as every such plant keeps it: the torque its
// drive applied since the plant's last step, integrated, and the channel's state at that step,
// extrapolated by its rate until the next (a sample-and-hold of the simulation with a first-order
// hold for the encoder), and whether the drive's mechanism was jammed. Real-time safe.

#include "teleop/drive/drive_plant.h"

namespace teleop::drive {

class SampledChannel : public DrivePlant {
 public:
  double position_rad() const override { return q_rad_ + dq_radps_ * elapsed_s_; }
  double velocity_radps() const override { return dq_radps_; }
  void apply(double torque_nm, double dt_s, bool jammed) override {
    impulse_nms_ += torque_nm * dt_s;
    elapsed_s_ += dt_s;
    jammed_ = jammed;
  }

  /// The mean torque applied since the last step (0 when none was).
  double mean_torque_nm() const { return elapsed_s_ > 0 ? impulse_nms_ / elapsed_s_ : 0.0; }
  /// The drive said its mechanism is jammed (a stall injected, its holding brake engaged).
  bool jammed() const { return jammed_; }
  /// The angle at the last step, as the channel reports it.
  double sampled_rad() const { return q_rad_; }
  /// The plant stepped: the channel's new state; the torque integrates from nothing again.
  void sample(double q_rad, double dq_radps) {
    q_rad_ = q_rad;
    dq_radps_ = dq_radps;
    impulse_nms_ = 0.0;
    elapsed_s_ = 0.0;
  }

 private:
  double q_rad_ = 0.0;  // at the last step
  double dq_radps_ = 0.0;
  double impulse_nms_ = 0.0;  // torque applied since, integrated over time
  double elapsed_s_ = 0.0;
  bool jammed_ = false;
};

}  // namespace teleop::drive
