#include "press_scenario.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "sweep_parameters.h"
#include "teleop/control/arm_dynamics.h"
#include "teleop/control/controllers.h"
#include "teleop/twin/twin_simulation.h"
#include "twin_arm_state.h"

namespace teleop::experiment {
namespace {

// writes one parameter value into the model (or the scenario)
void apply(const SweepParameter& p, double value, sim::MujocoModel& sim, PressScenario& press) {
  if (is_model_parameter(p.set)) {
    apply_model_parameter(p, value, sim);
  } else {
    press.depth_m = value;
  }
}

VariantOutcome run(const SweepConfig& config, const std::vector<double>& values) {
  VariantOutcome out;
  out.values = values;
  twin::TwinSimulation sim(config.model);
  PressScenario press = config.press;
  for (size_t i = 0; i < values.size(); ++i) apply(config.parameters[i], values[i], sim.simulation(), press);
  sim.reset();
  if (sim.contact_pairs().size() == 0) throw std::runtime_error("the sweep's model needs a contact pair to measure");

  control::ArmDynamics dynamics(sim.simulation().model(), press.site);
  control::CartesianImpedance::Gains gains;
  gains.translational_stiffness.setConstant(press.stiffness_n_per_m);
  control::CartesianImpedance controller(dynamics, gains);
  dynamics.update(arm_state(sim));
  control::ArmCommand command;
  const Eigen::Vector3d start = dynamics.ee_position();
  command.orientation_d = Eigen::Quaterniond(dynamics.ee_rotation());
  command.q_rest = dynamics.state().q;

  const double dt = sim.simulation().model()->opt.timestep;
  const int steps = static_cast<int>(std::lround(config.duration_s / dt));
  const int tail_from = steps - steps / 4;
  double tail_sum = 0.0;
  JointVector tau{};
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const double progress = std::min(1.0, k * dt / press.approach_time_s);
    command.x_d = start - Eigen::Vector3d(0, 0, press.depth_m * progress);
    const control::ArmState state = arm_state(sim);
    // the simulation compensates the bias forces itself: the controller's own estimate comes off
    const control::JointVector t = controller.compute(state, command) - dynamics.bias();
    for (int i = 0; i < control::kDof; ++i) tau[static_cast<size_t>(i)] = t[i];
    sim.step_torque(tau);
    const twin::Wrench w = sim.contact_wrench(0);
    const double force = std::sqrt(w.force_n[0] * w.force_n[0] + w.force_n[1] * w.force_n[1] + w.force_n[2] * w.force_n[2]);
    if (sim.contact_count(0) > 0) ++out.contact_steps;
    out.peak_force_n = std::max(out.peak_force_n, force);
    if (k >= tail_from) tail_sum += force;
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.rt_factor = out.wall_time_s > 0 ? steps * dt / out.wall_time_s : 0.0;
  out.mean_force_n = tail_sum / std::max(1, steps - tail_from);
  dynamics.update(arm_state(sim));
  out.final_error_m = (command.x_d - dynamics.ee_position()).norm();
  out.mujoco_warnings = sim.warnings();
  return out;
}

}  // namespace

VariantOutcome run_press_variant(const SweepConfig& config, const std::vector<double>& values) {
  try {
    return run(config, values);
  } catch (const std::exception& e) {
    VariantOutcome failed;
    failed.values = values;
    failed.error = e.what();
    return failed;
  }
}

}  // namespace teleop::experiment
