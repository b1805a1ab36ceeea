#pragma once
// The drive's own plant, its default (EmulatedDrive without a plant given): a finger link on the
// gearbox output between two hard stops (penalty spring-dampers that only push), with viscous
// friction and the rotor's inertia reflected through the gearbox. Advanced by the drive itself,
// one substep at a time; plain arithmetic, real-time safe.

#include "teleop/drive/drive_plant.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

class LinkPlant final : public DrivePlant {
 public:
  /// `params` must outlive the plant (the drive's configuration).
  LinkPlant(const EmulatedMotorParams& params, double initial_position_rad);

  double position_rad() const override { return q_rad_; }
  double velocity_radps() const override { return dq_radps_; }
  /// J ddq = torque - b dq + stops, semi-implicit Euler over dt_s; jammed: dq = 0.
  void apply(double torque_nm, double dt_s, bool jammed) override;

 private:
  const EmulatedMotorParams& params_;
  double inertia_kgm2_;  // link + rotor * gear ratio^2
  double q_rad_;
  double dq_radps_ = 0.0;
};

}  // namespace teleop::drive
