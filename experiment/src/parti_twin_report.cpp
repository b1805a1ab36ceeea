// The PARTI twin study's file, CSVs, report beside the paper's §3.2 and figures.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "report_files.h"
#include "teleop/common/config.h"
#include "teleop/common/joint_config.h"
#include "teleop/experiment/parti_twin_study.h"
#include "teleop/experiment/plots.h"
#include "teleop/sim/model_config.h"

namespace teleop::experiment {
namespace {

control::JointVector joint_values(const ConfigNode& node, const std::string& key, Range range) {
  const std::vector<double> v = node.get_double_list(key, range);
  if (v.size() != static_cast<size_t>(control::kDof)) throw node.error(key, "needs one value per joint (7)");
  return Eigen::Map<const control::JointVector>(v.data());
}

Eigen::Vector3d vector3(const ConfigNode& node, const std::string& key, Range range) {
  const std::array<double, 3> v = read_vector3(node, key, range);
  return {v[0], v[1], v[2]};
}

void read_controller(const ConfigNode& s, control::CartesianImpedance::Gains& g) {
  g.translational_stiffness = vector3(s, "translational_stiffness", Range{0, 1e5});
  g.rotational_stiffness = vector3(s, "rotational_stiffness", Range{0, 1e4});
  g.damping_ratio = s.get_double("damping_ratio", Range{0, 10}, g.damping_ratio);
  g.nullspace_stiffness = joint_values(s, "nullspace_stiffness", Range{0, 1e4});
  g.nullspace_damping = joint_values(s, "nullspace_damping", Range{0, 1e3});
}

// a signal over the runs: the mean of the runs' values and their range
struct Spread {
  double mean = 0.0;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
};
template <typename Get>
Spread spread(const std::vector<PartiTwinRun>& runs, Get&& get) {
  Spread s;
  for (const PartiTwinRun& r : runs) {
    const double v = get(r);
    s.mean += v;
    s.lo = std::min(s.lo, v);
    s.hi = std::max(s.hi, v);
  }
  s.mean /= static_cast<double>(std::max<size_t>(1, runs.size()));
  return s;
}
std::string cell(const Spread& s) {
  return format_number("%.3g", s.mean) + " (" + format_number("%.3g", s.lo) + "–" + format_number("%.3g", s.hi) + ")";
}

std::string trace_csv(const std::vector<PartiTwinRun>& runs, double period_s) {
  std::ostringstream out;
  out << "seed,t_s,phase,contact,ee_position_mm,ee_rotation_mrad,force_error_n,moment_error_nm,f_true_z_n,f_twin_z_n";
  for (int i = 0; i < kEstimatorCount; ++i) out << ",f_" << estimator_name(i) << "_z_n";
  for (int i = 0; i < kEstimatorCount; ++i) out << ",err_" << estimator_name(i) << "_n";
  out << '\n';
  for (const PartiTwinRun& r : runs) {
    const double dt = r.t_s.size() > 1 ? r.t_s[1] - r.t_s[0] : period_s;
    const size_t every = std::max<size_t>(1, static_cast<size_t>(std::lround(period_s / dt)));
    for (size_t k = every - 1; k < r.t_s.size(); k += every) {
      out << r.seed << ',' << format_number("%.3f", r.t_s[k]) << ',' << phase_name(r.phase[k]) << ','
          << (r.phase[k] == kFree ? 0 : 1) << ',' << format_number("%.4f", r.position_mm[k]) << ','
          << format_number("%.4f", r.rotation_mrad[k]) << ',' << format_number("%.4f", r.force_error_n[k]) << ','
          << format_number("%.4f", r.moment_error_nm[k]) << ',' << format_number("%.4f", r.f_true_z_n[k]) << ','
          << format_number("%.4f", r.f_twin_z_n[k]);
      for (int i = 0; i < kEstimatorCount; ++i) out << ',' << format_number("%.4f", r.f_estimate_z_n[i][k]);
      for (int i = 0; i < kEstimatorCount; ++i) out << ',' << format_number("%.4f", r.estimate_error_n[i][k]);
      out << '\n';
    }
  }
  return out.str();
}

std::string phases_csv(const std::vector<PartiTwinRun>& runs) {
  std::ostringstream out;
  out << "seed,phase,samples,position_mean_mm,position_max_mm,force_error_mean_n,force_error_max_n";
  for (int i = 0; i < kEstimatorCount; ++i) out << ',' << estimator_name(i) << "_mean_n," << estimator_name(i) << "_max_n";
  out << '\n';
  for (const PartiTwinRun& r : runs) {
    for (int p = 0; p < kPhaseCount; ++p) {
      out << r.seed << ',' << phase_name(p) << ',' << r.position[p].samples << ','
          << format_number("%.5g", r.position[p].mean) << ',' << format_number("%.5g", r.position[p].max) << ','
          << format_number("%.5g", r.force[p].mean) << ',' << format_number("%.5g", r.force[p].max);
      for (int i = 0; i < kEstimatorCount; ++i) {
        out << ',' << format_number("%.5g", r.estimator[i][p].mean) << ',' << format_number("%.5g", r.estimator[i][p].max);
      }
      out << '\n';
    }
  }
  return out.str();
}

constexpr const char* kEstimatorLabels[] = {
    "momentum observer (eqs. 6-8)", "PARTI eq. 5, τ_d = 0, τ_m = τ_J: g(q) − τ_J",
    "PARTI eq. 5, τ_d = eq. 4's torque beyond gravity, τ_m = τ_J", "direct with M q̈ + n (Haddadin)"};
// what PARTI's §3.2 says of each, in words (its text gives no numbers)
constexpr const char* kPartiSays[] = {
    "matches the robot's own estimate in contact; small high-frequency noise, sensitive to motion",
    "Gazebo's estimator: overestimated in free motion (uncompensated inertia), greater in contact", "(as above)",
    "– (not in the paper)"};

}  // namespace

PartiTwinConfig load_parti_twin_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("parti_twin_study");
  PartiTwinConfig c;
  c.file = path;
  c.name = s.get_string("name");
  c.model_path = sim::get_model_path(s, "model");
  c.ee_site = s.get_string("ee_site", c.ee_site);
  c.keyframe = s.get_string("keyframe");
  for (const double seed : s.get_double_list("seeds", Range{0, 9007199254740992.0})) {
    if (seed != std::floor(seed)) throw s.error("seeds", "holds " + std::to_string(seed) + ", not a whole number");
    c.seeds.push_back(static_cast<uint64_t>(seed));
  }
  if (c.seeds.empty()) throw s.error("seeds", "lists no seed");
  c.start_hold_s = s.get_double("start_hold_s", Range{0.1, 60}, c.start_hold_s);
  std::set<std::string> names;
  for (const ConfigNode& w : s.get_node_list("waypoints")) {
    PartiWaypoint p;
    p.name = w.get_string("name");
    if (!names.insert(p.name).second) throw w.error("name", "'" + p.name + "' is a second waypoint of that name");
    p.position_m = vector3(w, "position_m", Range{-3, 3});
    p.move_s = w.get_double("move_s", Range{0.05, 600});
    p.hold_s = w.get_double("hold_s", Range{0, 600}, 0.0);
    c.waypoints.push_back(p);
  }
  if (c.waypoints.empty()) throw s.error("waypoints", "lists no waypoint");
  read_controller(s.child("controller"), c.gains);
  c.observer_gain_per_s = s.get_double("observer_gain_per_s", Range{1, 1000}, c.observer_gain_per_s);
  c.direct_gamma = s.get_double("direct_gamma", Range{1e-4, 1}, c.direct_gamma);
  c.static_speed_mps = s.get_double("static_speed_mps", Range{0, 1}, c.static_speed_mps);
  c.trace_period_s = s.get_double("trace_period_s", Range{1e-3, 10}, c.trace_period_s);
  const ConfigNode real = s.child("real_robot");
  c.perturbation = sim::read_perturbation(real.child("perturbation"));
  c.sensor_noise = sim::read_sensor_noise(real.child("sensor_noise"));
  root.check_all_used();
  return c;
}

std::string format_parti_twin_markdown(const PartiTwinConfig& c, const std::vector<PartiTwinRun>& runs) {
  std::ostringstream out;
  out << "# " << c.name << ": PARTI §3.2, the twin against the real robot with table contacts\n\n"
      << "Seeds " << runs.size() << " (one perturbed \"real\" robot each); cells: the mean over the seeds (their "
      << "range). Errors per phase of the real robot: free motion, contact (pressing and sliding), static "
      << "contact (in contact, end effector slower than " << format_number("%g", 1000 * c.static_speed_mps)
      << " mm/s). Contact force in static contact: "
      << cell(spread(runs, [](const PartiTwinRun& r) { return r.static_force_n; })) << " N; largest (the touchdown's "
      << "impact): " << cell(spread(runs, [](const PartiTwinRun& r) { return r.peak_force_n; })) << " N.\n\n## The twin against the real robot (PARTI Fig. 7)\n\n"
      << "| phase | position error mean [mm] | max [mm] | contact-force error mean [N] | max [N] |\n"
      << "|---|---|---|---|---|\n";
  for (int p = 0; p < kPhaseCount; ++p) {
    out << "| " << phase_name(p) << " | " << cell(spread(runs, [p](const PartiTwinRun& r) { return r.position[p].mean; }))
        << " | " << cell(spread(runs, [p](const PartiTwinRun& r) { return r.position[p].max; })) << " | "
        << cell(spread(runs, [p](const PartiTwinRun& r) { return r.force[p].mean; })) << " | "
        << cell(spread(runs, [p](const PartiTwinRun& r) { return r.force[p].max; })) << " |\n";
  }
  out << "\nPARTI prints no numbers for Fig. 7; it reports the MuJoCo twin closer to the real Panda than "
         "Franka's Gazebo model.\n\n## The estimators on the real robot against its true contact force "
         "(PARTI Fig. 6, right)\n\n"
      << "| estimator | free: mean [N] | free: max [N] | contact: mean [N] | static contact: mean [N] | static "
         "contact: max [N] | PARTI §3.2 says |\n|---|---|---|---|---|---|---|\n";
  for (int i = 0; i < kEstimatorCount; ++i) {
    const auto est = [i](int p, bool max) {
      return [i, p, max](const PartiTwinRun& r) { return max ? r.estimator[i][p].max : r.estimator[i][p].mean; };
    };
    out << "| " << kEstimatorLabels[i] << " | " << cell(spread(runs, est(kFree, false))) << " | "
        << cell(spread(runs, est(kFree, true))) << " | " << cell(spread(runs, est(kContact, false))) << " | "
        << cell(spread(runs, est(kStaticContact, false))) << " | " << cell(spread(runs, est(kStaticContact, true)))
        << " | " << kPartiSays[i] << " |\n";
  }
  int warnings = 0;
  for (const PartiTwinRun& r : runs) warnings += r.mujoco_warnings;
  out << "\nError: |F_est − F_true|, the force at the end effector (eq. 8 through the pseudo-inverse of J^T). "
         "MuJoCo warnings: "
      << warnings << ".\n";
  return out.str();
}

PartiTwinResult run_parti_twin_study(const PartiTwinConfig& c, const std::vector<uint64_t>& seeds,
                                     const std::string& out_dir, bool plots) {
  PartiTwinResult result;
  for (const uint64_t seed : seeds.empty() ? c.seeds : seeds) result.runs.push_back(run_parti_twin_case(c, seed));
  result.out_dir = make_report_dir(out_dir, "teleop-" + c.name + "-");
  const std::filesystem::path dir(result.out_dir);
  result.trace_csv = (dir / (c.name + "_trace.csv")).string();
  result.phases_csv = (dir / (c.name + "_phases.csv")).string();
  result.markdown = (dir / (c.name + ".md")).string();
  write_text(result.trace_csv, trace_csv(result.runs, c.trace_period_s));
  write_text(result.phases_csv, phases_csv(result.runs));
  write_text(result.markdown, format_parti_twin_markdown(c, result.runs));
  if (plots) {
    try {
      plot_parti_study(find_plot_tool(), "twin", result.trace_csv, result.out_dir);
    } catch (const PlotError& e) {
      result.plot_error = e.what();
    }
  }
  return result;
}

}  // namespace teleop::experiment
