// The fidelity study's runs: the "real" run, its replay in lock-step, and the comparison per pose
// and movement (thesis §4.1-4.2).
#include "teleop/experiment/fidelity_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "fidelity_arm.h"
#include "teleop/control/min_jerk.h"

namespace teleop::experiment {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> as_vector(const control::JointVector& q) { return {q.data(), q.data() + q.size()}; }

// the sequence's commanded motion: hold_s at the start, then per pose move_s of minimum jerk and
// hold_s at rest
control::MinJerkPath sequence_path(const FidelityStudyConfig& c, const FidelitySequence& s) {
  std::vector<double> at = as_vector(c.pose(s.path.front()).q_rad);
  control::MinJerkPath path(at);
  path.then(at, c.hold_s);
  for (size_t i = 1; i < s.path.size(); ++i) {
    at = as_vector(c.pose(s.path[i]).q_rad);
    path.then(at, c.move_s);
    path.then(at, c.hold_s);
  }
  return path;
}

long sequence_steps(const FidelityStudyConfig& c, const FidelitySequence& s, double timestep_s) {
  const double duration_s = c.hold_s + static_cast<double>(s.path.size() - 1) * (c.move_s + c.hold_s);
  return std::lround(duration_s / timestep_s);
}

// the poses held (each once, at its first visit) and the movements, with their windows
std::vector<FidelitySegment> sequence_segments(const FidelityStudyConfig& c, const FidelitySequence& s) {
  std::vector<FidelitySegment> out;
  const auto seen = [&](const std::string& name) {
    return std::any_of(out.begin(), out.end(), [&](const FidelitySegment& g) { return g.name == name; });
  };
  double arrive_s = 0.0;
  for (size_t i = 0; i < s.path.size(); ++i) {
    if (i > 0) {
      const double start_s = arrive_s + c.hold_s;
      FidelitySegment move;
      move.name = s.path[i - 1] + "_to_" + s.path[i];
      move.movement = true;
      move.window = {start_s - c.movement_before_s, start_s + c.move_s + c.movement_after_s};
      if (!seen(move.name)) out.push_back(move);
      arrive_s = start_s + c.move_s;
    }
    FidelitySegment pose;
    pose.name = s.path[i];
    pose.window = {arrive_s + c.hold_s - c.pose_window_s, arrive_s + c.hold_s};
    if (!seen(pose.name)) out.push_back(pose);
  }
  // in time order: a movement's window begins before the pose held ahead of it ends
  std::stable_sort(out.begin(), out.end(),
                   [](const FidelitySegment& a, const FidelitySegment& b) { return a.window.end_s < b.window.end_s; });
  return out;
}

// runs `arm` through `commands` (one lock-step each), keeping the measurements and timing each step
FidelityTrajectory drive(FidelityArm& arm, const control::JointVector& start,
                         const std::vector<RecordedCommand>& commands) {
  FidelityTrajectory out;
  out.q_rad.reserve(commands.size());
  out.dq_radps.reserve(commands.size());
  out.tau_nm.reserve(commands.size());
  arm.place(start);
  using Clock = std::chrono::steady_clock;
  for (const RecordedCommand& command : commands) {
    const Clock::time_point before = Clock::now();
    arm.step(command);
    const double took_s = std::chrono::duration<double>(Clock::now() - before).count();
    out.computing_s += took_s;
    if (arm.in_contact()) {
      ++out.contact_steps;
      out.contact_computing_s += took_s;
    }
    out.q_rad.push_back(arm.measured().q);
    out.dq_radps.push_back(arm.measured().dq);
    out.tau_nm.push_back(arm.tau_measured());
  }
  out.timestep_s = arm.timestep_s();
  out.mujoco_warnings = arm.mujoco_warnings();
  out.perturbation = arm.perturbation();
  return out;
}

// max over the joints of the mean |a_i - b_i| over the samples in `w`
double largest_mean_error(const std::vector<double>& t_s, const std::vector<control::JointVector>& a,
                          const std::vector<control::JointVector>& b, Window w) {
  control::JointVector sum = control::JointVector::Zero();
  size_t n = 0;
  for (size_t k = 0; k < t_s.size(); ++k) {
    if (!w.contains(t_s[k])) continue;
    sum += (a[k] - b[k]).cwiseAbs();
    ++n;
  }
  return n == 0 ? kNaN : sum.maxCoeff() / static_cast<double>(n);
}

}  // namespace

const char* controller_name(FidelityController controller) {
  switch (controller) {
    case FidelityController::kStateSpace: return "state_space";
    case FidelityController::kJointImpedance: return "joint_impedance";
    case FidelityController::kCartesianImpedance: return "cartesian_impedance";
  }
  return "?";
}

const FidelityPose& FidelityStudyConfig::pose(const std::string& pose_name) const {
  for (const FidelityPose& p : poses) {
    if (p.name == pose_name) return p;
  }
  throw std::out_of_range(file + ": no pose '" + pose_name + "'");
}

FidelityTrajectory run_real(const FidelityStudyConfig& c, const FidelitySequence& s, FidelityController controller,
                            uint64_t seed, std::vector<RecordedCommand>& commands) {
  FidelityArm arm(c, s.model_path, controller, seed);
  const control::MinJerkPath path = sequence_path(c, s);
  const double dt = arm.timestep_s();
  const long steps = sequence_steps(c, s, dt);
  // the commands are the planned motion, sampled at each step (thesis §3.3: desired positions and
  // velocities; mode and gains are the run's)
  commands.assign(static_cast<size_t>(steps), RecordedCommand{});
  for (long k = 0; k < steps; ++k) {
    RecordedCommand& command = commands[static_cast<size_t>(k)];
    path.sample(static_cast<double>(k) * dt, std::span<double>(command.q_d.data(), control::kDof),
                std::span<double>(command.dq_d.data(), control::kDof));
  }
  return drive(arm, c.pose(s.path.front()).q_rad, commands);
}

FidelityTrajectory replay(const FidelityStudyConfig& c, const FidelitySequence& s, FidelityController controller,
                          const std::vector<RecordedCommand>& commands) {
  FidelityArm arm(c, s.model_path, controller, std::nullopt);
  return drive(arm, c.pose(s.path.front()).q_rad, commands);
}

FidelityRun run_fidelity_case(const FidelityStudyConfig& c, const FidelitySequence& s, FidelityController controller,
                              uint64_t seed) {
  std::vector<RecordedCommand> commands;
  const FidelityTrajectory real = run_real(c, s, controller, seed, commands);
  const FidelityTrajectory twin = replay(c, s, controller, commands);

  FidelityRun run;
  run.sequence = s.name;
  run.contact = s.contact;
  run.controller = controller;
  run.seed = seed;
  run.perturbation = real.perturbation;
  run.mujoco_warnings = real.mujoco_warnings + twin.mujoco_warnings;
  const double dt = twin.timestep_s;
  run.free_steps = commands.size() - twin.contact_steps;
  run.contact_steps = twin.contact_steps;
  const double free_computing_s = twin.computing_s - twin.contact_computing_s;
  const auto rt_factor = [dt](size_t steps, double computing_s) {
    return steps > 0 && computing_s > 0 ? static_cast<double>(steps) * dt / computing_s : kNaN;
  };
  run.rt_factor_free = rt_factor(run.free_steps, free_computing_s);
  run.rt_factor_contact = rt_factor(run.contact_steps, twin.contact_computing_s);

  // the thesis's metrics at every step: joints in degrees, torques in N m, the end effector by
  // the nominal forward kinematics of each run's measured joints (its "forward kinematics
  // position", §4.1.3)
  ForwardKinematics fk(s.model_path, c.ee_site);
  FidelitySignals& sig = run.signals;
  const size_t n = commands.size();
  for (std::vector<double>* v : {&sig.t_s, &sig.q_rmse_deg, &sig.q_max_joint_deg, &sig.tau_rmse_nm,
                                 &sig.tau_max_joint_nm, &sig.ee_position_cm, &sig.ee_rotation}) {
    v->reserve(n);
  }
  std::array<double, control::kDof> e{};
  std::array<double, 3> p_real{};
  std::array<double, 3> p_twin{};
  Quaternion r_real{};
  Quaternion r_twin{};
  for (size_t k = 0; k < n; ++k) {
    sig.t_s.push_back(static_cast<double>(k + 1) * dt);
    for (int i = 0; i < control::kDof; ++i)
      e[static_cast<size_t>(i)] = (real.q_rad[k][i] - twin.q_rad[k][i]) * kDegPerRad;
    sig.q_rmse_deg.push_back(rmse(e));
    sig.q_max_joint_deg.push_back(max_abs(e));
    for (int i = 0; i < control::kDof; ++i) e[static_cast<size_t>(i)] = real.tau_nm[k][i] - twin.tau_nm[k][i];
    sig.tau_rmse_nm.push_back(rmse(e));
    sig.tau_max_joint_nm.push_back(max_abs(e));
    fk.pose(real.q_rad[k], p_real, r_real);
    fk.pose(twin.q_rad[k], p_twin, r_twin);
    const double dx = p_real[0] - p_twin[0];
    const double dy = p_real[1] - p_twin[1];
    const double dz = p_real[2] - p_twin[2];
    sig.ee_position_cm.push_back(100.0 * std::sqrt(dx * dx + dy * dy + dz * dz));
    sig.ee_rotation.push_back(rotation_distance(r_real, r_twin));
  }
  run.segments = sequence_segments(c, s);
  for (FidelitySegment& g : run.segments) {
    g.q_rmse_deg = summarize_in(sig.t_s, sig.q_rmse_deg, g.window);
    g.tau_rmse_nm = summarize_in(sig.t_s, sig.tau_rmse_nm, g.window);
    g.ee_position_cm = summarize_in(sig.t_s, sig.ee_position_cm, g.window);
    g.ee_rotation = summarize_in(sig.t_s, sig.ee_rotation, g.window);
    if (g.movement) {
      // the largest single-joint error at any sample of the movement
      g.q_max_joint_deg = summarize_in(sig.t_s, sig.q_max_joint_deg, g.window).max;
      g.tau_max_joint_nm = summarize_in(sig.t_s, sig.tau_max_joint_nm, g.window).max;
    } else {
      // a pose's errors averaged over its window (§4.2.2: "averaged over five hundred samples to
      // avoid any outliers"): the largest joint's mean |error|
      g.q_max_joint_deg = largest_mean_error(sig.t_s, real.q_rad, twin.q_rad, g.window) * kDegPerRad;
      g.tau_max_joint_nm = largest_mean_error(sig.t_s, real.tau_nm, twin.tau_nm, g.window);
    }
  }
  return run;
}

FidelityCell aggregate(const FidelityRun& run, bool movements) {
  const auto over = [&](auto field) {
    FidelityAggregate a{0.0, 0.0, 0.0};
    size_t n = 0;
    for (const FidelitySegment& g : run.segments) {
      if (g.movement != movements) continue;
      const Summary& s = field(g);
      a.mean += s.mean;
      // a movement's peak at any sample; a pose's value is its mean over its window (§4.2.2)
      a.max = std::max(a.max, movements ? s.max : s.mean);
      ++n;
    }
    if (n == 0) return FidelityAggregate{kNaN, kNaN, kNaN};
    a.mean /= static_cast<double>(n);
    for (const FidelitySegment& g : run.segments) {
      if (g.movement == movements) a.sd += (field(g).mean - a.mean) * (field(g).mean - a.mean);
    }
    a.sd = std::sqrt(a.sd / static_cast<double>(n));
    return a;
  };
  FidelityCell cell;
  cell.q_rmse_deg = over([](const FidelitySegment& g) -> const Summary& { return g.q_rmse_deg; });
  cell.tau_rmse_nm = over([](const FidelitySegment& g) -> const Summary& { return g.tau_rmse_nm; });
  cell.ee_position_cm = over([](const FidelitySegment& g) -> const Summary& { return g.ee_position_cm; });
  cell.ee_rotation = over([](const FidelitySegment& g) -> const Summary& { return g.ee_rotation; });
  for (const FidelitySegment& g : run.segments) {
    if (g.movement != movements) continue;
    cell.q_max_joint_deg = std::max(cell.q_max_joint_deg, g.q_max_joint_deg);
    cell.tau_max_joint_nm = std::max(cell.tau_max_joint_nm, g.tau_max_joint_nm);
  }
  return cell;
}

}  // namespace teleop::experiment
