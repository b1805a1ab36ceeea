#pragma once
// What an emulated drive's motor turns: the plant behind the gearbox. The drive (EmulatedDrive)
// runs its current loop on the winding and hands the resulting torque at the gearbox output to
// its plant every substep; its encoder reads the plant's output angle. Two kinds of plant:
//   - each drive's own link between hard stops (the default, EmulatedDrive's light DC-motor
//     model, drive/src/link_plant.h), advanced by the drive itself;
//   - one shared simulation that all drives of a hand turn together (the MuJoCo hand,
//     teleop/hand/mujoco_drive_plants.h): it advances in fixed steps, after every drive has
//     put in its torque for the step. DriveGroup (drive_group.h) keeps the drives and such
//     a plant in lock-step.
// Units: output side (after the gearbox): rad, rad/s, N m. Real-time safe: no allocation, no
// exceptions, no blocking in any of these calls.

#include <cstddef>

namespace teleop::drive {

/// The mechanics one drive turns, seen from its gearbox output.
class DrivePlant {
 public:
  virtual ~DrivePlant() = default;

  /// Output angle [rad] and rate [rad/s] now, as the encoder and the winding's back-EMF see them.
  virtual double position_rad() const = 0;
  virtual double velocity_radps() const = 0;
  /// The motor's torque at the gearbox output [N m] acts for the next dt_s. `jammed`: the
  /// mechanism is blocked (fault injection): it does not move, whatever the torque.
  virtual void apply(double torque_nm, double dt_s, bool jammed) = 0;
};

/// The plant of several drives that advances as one, in steps of step_s(): every drive applies
/// its torque for one step (apply() over the step, in any number of pieces), then step()
/// advances the whole, with each channel's torque averaged over the step. Between two step()
/// calls a channel reports its state at the last step, extrapolated by its velocity over the time
/// applied since (a sample-and-hold of the simulation with a first-order hold for the encoder).
class SharedDrivePlant {
 public:
  virtual ~SharedDrivePlant() = default;

  /// Number of channels (one per drive, in the hand's motor order).
  virtual size_t channels() const = 0;
  virtual DrivePlant& channel(size_t k) = 0;
  /// The fixed step [s] the plant advances by.
  virtual double step_s() const = 0;
  /// Advances by step_s() with the torques applied since the last step (a channel nobody
  /// applied a torque to gets none). Real-time safe.
  virtual void step() = 0;
};

}  // namespace teleop::drive
