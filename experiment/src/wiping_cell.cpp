// One cell of the wiping study: the world of one wiper angle and panel height, the plan made for
// the assumed ones, three wipes under Cartesian impedance, and what each wipe did.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "sweep_parameters.h"
#include "teleop/control/arm_dynamics.h"
#include "teleop/control/controllers.h"
#include "teleop/control/estimators.h"
#include "teleop/experiment/wiping_study.h"
#include "teleop/twin/twin_simulation.h"
#include "twin_arm_state.h"
#include "wiping_trajectory.h"

namespace teleop::experiment {
namespace {

Eigen::Isometry3d site_pose(const mjData* d, int site) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Map<const Eigen::Vector3d>(d->site_xpos + 3 * site);
  pose.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * site);
  return pose;
}

void set_world(const WipingStudyConfig& c, double angle_rad, double height_m, twin::TwinSimulation& sim) {
  apply_model_parameter({c.wiper_angle.name, c.wiper_angle.set, {}}, angle_rad, sim.simulation());
  apply_model_parameter({c.panel_height.name, c.panel_height.set, {}}, height_m, sim.simulation());
  sim.reset();
}

// the plan: made in the world the planner assumed (the planned angle and height), from the start
// pose of the keyframe
WipingTrajectory make_plan(const WipingStudyConfig& c, twin::TwinSimulation& sim) {
  set_world(c, c.wiper_angle.planned, c.panel_height.planned, sim);
  const mjModel* m = sim.simulation().model();
  const mjData* d = sim.simulation().data();
  const Eigen::Isometry3d hand = site_pose(d, sim.simulation().site_id(c.hand_site));
  const Eigen::Isometry3d tool = site_pose(d, sim.simulation().site_id(c.tool_site));
  const int panel = sim.simulation().geom_id(c.panel_geom);
  // the box's axes: z its normal, x up its slope (the scene tilts it about y), y across
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->geom_xmat + 9 * panel);
  PanelFrame frame;
  frame.n = r.col(2);
  frame.v = r.col(0);
  frame.u = r.col(1);
  frame.centre = Eigen::Map<const Eigen::Vector3d>(d->geom_xpos + 3 * panel) + m->geom_size[3 * panel + 2] * frame.n;
  return WipingTrajectory(c.plan, frame, hand.inverse() * tool, hand);
}

// what one step adds to the wipe whose window holds it (or to the free-motion peaks)
void record(const twin::TwinSimulation& sim, const control::JointVector& tau_ext, double force_n, double threshold_n,
            WipeOutcome* wipe, control::JointVector& free_peak) {
  if (wipe == nullptr) {
    free_peak = free_peak.cwiseMax(tau_ext.cwiseAbs());
    return;
  }
  wipe->tau_ext_peak_nm = wipe->tau_ext_peak_nm.cwiseMax(tau_ext.cwiseAbs());
  for (int i = 0; i < control::kDof; ++i) {
    wipe->constraint_peak_nm[i] =
        std::max(wipe->constraint_peak_nm[i], std::abs(sim.constraint_torque_nm()[static_cast<size_t>(i)]));
  }
  wipe->peak_force_n = std::max(wipe->peak_force_n, force_n);
  if (sim.contact_count(0) > 0 && force_n > threshold_n) {
    wipe->contact = true;
    ++wipe->contact_steps;
    wipe->mean_force_n += force_n;  // a sum until the run ends
  }
}

// the trace's rows: one every kTracePeriodSteps steps
constexpr int kTracePeriodSteps = 10;

void trace_row(std::ofstream& out, const WipingCell& cell, double t_s, const control::JointVector& tau_ext,
               double force_n, double hand_z_m) {
  out << cell.wiper_angle_rad << ',' << cell.panel_height_m << ',' << t_s;
  for (int i = 0; i < control::kDof; ++i) out << ',' << tau_ext[i];
  out << ',' << force_n << ',' << hand_z_m << '\n';
}

WipingCell run(const WipingStudyConfig& c, double angle_rad, double height_m, const std::string& trace_path) {
  WipingCell cell;
  cell.wiper_angle_rad = angle_rad;
  cell.panel_height_m = height_m;
  twin::TwinSimulation sim(c.model);
  if (sim.contact_pairs().size() == 0) throw std::runtime_error("the study's model needs the wiper-panel contact pair");
  const WipingTrajectory plan = make_plan(c, sim);
  set_world(c, angle_rad, height_m, sim);

  control::ArmDynamics dynamics(sim.simulation().model(), c.hand_site);
  control::CartesianImpedance::Gains gains;
  gains.translational_stiffness.setConstant(c.translational_stiffness_n_per_m);
  gains.rotational_stiffness.setConstant(c.rotational_stiffness_nm_per_rad);
  control::CartesianImpedance controller(dynamics, gains);
  const double dt = sim.simulation().model()->opt.timestep * sim.substeps();
  control::MomentumObserver observer(dynamics, dt, control::JointVector::Constant(c.observer_gain_per_s));
  control::ArmCommand command;
  command.q_rest = arm_state(sim).q;
  observer.update(arm_state(sim), control::JointVector::Zero());

  const auto& windows = plan.wipe_windows();
  cell.wipes.assign(windows.size(), WipeOutcome{});
  const int steps = static_cast<int>(std::lround(plan.duration_s() / dt));
  const double free_from_s = windows.front().first;
  std::ofstream trace;
  if (!trace_path.empty()) {
    trace.open(trace_path);
    trace.precision(6);
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const HandSetPoint set_point = plan.at(k * dt);
    command.x_d = set_point.position;
    command.orientation_d = set_point.orientation;
    command.twist_d = set_point.twist;
    const control::ArmState state = arm_state(sim);
    const control::JointVector tau = controller.compute(state, command);
    // the simulation compensates the bias forces itself: the controller's own estimate comes off
    const control::JointVector commanded = tau - dynamics.bias();
    JointVector applied{};
    for (int i = 0; i < control::kDof; ++i) applied[static_cast<size_t>(i)] = commanded[i];
    sim.step_torque(applied);
    // the observer sees what the joints were told to apply, bias compensation included: tau
    const control::JointVector& tau_ext = observer.update(arm_state(sim), tau);
    const twin::Wrench w = sim.contact_wrench(0);
    const double force =
        std::sqrt(w.force_n[0] * w.force_n[0] + w.force_n[1] * w.force_n[1] + w.force_n[2] * w.force_n[2]);
    const double t = (k + 1) * dt;
    WipeOutcome* wipe = nullptr;
    for (size_t i = 0; i < windows.size(); ++i) {
      if (t >= windows[i].first && t <= windows[i].second) wipe = &cell.wipes[i];
    }
    if (wipe != nullptr || t >= free_from_s)
      record(sim, tau_ext, force, c.contact_force_n, wipe, cell.free_tau_ext_peak_nm);
    if (trace.is_open() && (k + 1) % kTracePeriodSteps == 0) {
      trace_row(trace, cell, t, tau_ext, force, dynamics.ee_position().z());
    }
  }
  for (WipeOutcome& w : cell.wipes) w.mean_force_n /= std::max(1, w.contact_steps);
  cell.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cell.sim_time_s = steps * dt;
  cell.mujoco_warnings = sim.warnings();
  return cell;
}

}  // namespace

int WipingCell::contacts() const {
  int n = 0;
  for (const WipeOutcome& w : wipes) n += w.contact ? 1 : 0;
  return n;
}

const char* const kWipingTraceColumns =
    "wiper_angle_rad,panel_height_m,t_s,tau_ext_j0_nm,tau_ext_j1_nm,tau_ext_j2_nm,tau_ext_j3_nm,tau_ext_j4_nm,"
    "tau_ext_j5_nm,tau_ext_j6_nm,force_n,hand_z_m";

WipingCell run_wiping_cell(const WipingStudyConfig& config, double wiper_angle_rad, double panel_height_m,
                           const std::string& trace_path) {
  try {
    return run(config, wiper_angle_rad, panel_height_m, trace_path);
  } catch (const std::exception& e) {
    WipingCell failed;
    failed.wiper_angle_rad = wiper_angle_rad;
    failed.panel_height_m = panel_height_m;
    failed.error = e.what();
    return failed;
  }
}

}  // namespace teleop::experiment
