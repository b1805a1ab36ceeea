#pragma once
// A "real" robot that differs from its model as in life (docs/fidelity.md): the arm's link
// masses, centres of mass, joint friction, viscous damping and rotor inertia off by amounts drawn
// within the uncertainty docs/models.md states ("Uncertainty"), and sensors with noise. Seeded:
// one seed gives the same robot and the same noise, bit for bit, on any machine (the draws use
// std::mt19937_64, whose output the standard fixes, and no std:: distribution, whose output it
// does not).

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/sim/actuated_joints.h"

namespace teleop::sim {

/// How far each quantity of the arm may be off; every link's and joint's value is drawn on its
/// own, uniformly within the bound (u in [-1, 1] unless stated).
struct PerturbationSpec {
  /// Link mass x (1 + u a); the inertia tensor scales with it (a uniformly denser link).
  double mass_fraction = 0.10;
  /// The centre of mass moves by u a along each axis of the link's frame [m].
  double com_offset_m = 0.01;
  /// Dry friction (MuJoCo frictionloss) x (1 + u a).
  double friction_fraction = 0.30;
  /// Viscous damping added to each joint, u' a with u' in [0, 1] [N m s/rad] (the model has none).
  double damping_max_nms_per_rad = 0.5;
  /// Rotor inertia (MuJoCo armature) x (1 + u a).
  double armature_fraction = 0.5;
};

/// Standard deviation of white Gaussian noise on each measured quantity.
struct SensorNoiseSpec {
  double q_rad = 1e-4;
  double dq_radps = 2e-3;
  double tau_nm = 0.05;
};

/// What was drawn, per actuated joint (and the link it moves), in actuator order.
struct AppliedPerturbation {
  uint64_t seed = 0;
  std::vector<double> mass_factor;
  std::vector<std::array<double, 3>> com_offset_m;
  std::vector<double> friction_factor;
  std::vector<double> damping_nms_per_rad;
  std::vector<double> armature_factor;
  /// The links' total mass before and after [kg].
  double nominal_mass_kg = 0.0;
  double perturbed_mass_kg = 0.0;
};

/// The random stream behind the perturbation and the noise: uniform and Gaussian numbers from
/// std::mt19937_64, computed here (53-bit uniforms, Box-Muller), so they are the same everywhere.
/// Real-time safe.
class SeededRandom {
 public:
  explicit SeededRandom(uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1).
  double uniform();
  /// Uniform in [-1, 1).
  double symmetric() { return 2.0 * uniform() - 1.0; }
  /// Standard normal.
  double gaussian();

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// Perturbs the bodies and degrees of freedom of `joints` in `m` (each joint's body is the link it
/// moves) by `spec`, drawn from `seed`, and recomputes the model's derived constants
/// (mj_setConst, which uses `d` as scratch: reset the data afterwards). Setup time: allocates.
AppliedPerturbation perturb_plant(mjModel* m, mjData* d, const ActuatedJoints& joints, const PerturbationSpec& spec,
                                  uint64_t seed);

/// Noise on the measurements of a run, drawn from a seed of its own. Real-time safe.
class SensorNoise {
 public:
  SensorNoise(const SensorNoiseSpec& spec, uint64_t seed) : spec_(spec), random_(seed) {}
  double q_rad() { return spec_.q_rad * random_.gaussian(); }
  double dq_radps() { return spec_.dq_radps * random_.gaussian(); }
  double tau_nm() { return spec_.tau_nm * random_.gaussian(); }
  const SensorNoiseSpec& spec() const { return spec_; }

 private:
  SensorNoiseSpec spec_;
  SeededRandom random_;
};

/// A "real" robot: how far it is from its model, how noisy its sensors are, and the seed that
/// draws both (the robot: derived_seed(seed, 0); the sensors: derived_seed(seed, 1), ...).
struct RealRobotSpec {
  uint64_t seed = 0;
  PerturbationSpec perturbation;
  SensorNoiseSpec sensor_noise;
};

/// Reads a `perturbation:` section (mass_fraction, com_offset_m, friction_fraction,
/// damping_max_nms_per_rad, armature_fraction), each key optional with the default above.
/// Throws ConfigError naming the file and key for a value out of range. Setup time.
PerturbationSpec read_perturbation(const ConfigNode& perturbation);
/// Reads a `sensor_noise:` section (q_rad, dq_radps, tau_nm), as read_perturbation().
SensorNoiseSpec read_sensor_noise(const ConfigNode& sensor_noise);
/// Reads a `real_robot:` section: `seed` (default 0), `perturbation:`, `sensor_noise:` (each
/// optional). Setup time.
RealRobotSpec read_real_robot(const ConfigNode& real_robot);

/// A seed of its own for each use of one run seed (`stream` 0: the robot, 1: its sensors, ...),
/// so that changing one use does not shift the draws of another (splitmix64).
uint64_t derived_seed(uint64_t seed, uint64_t stream);

}  // namespace teleop::sim
