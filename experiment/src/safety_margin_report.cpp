// The safety-margin study's file, its CSV, its report beside PARTI's Fig. 5 and its figure.
#include <filesystem>
#include <set>
#include <sstream>

#include "report_files.h"
#include "teleop/common/config.h"
#include "teleop/experiment/plots.h"
#include "teleop/experiment/safety_margin_study.h"
#include "teleop/sim/model_config.h"

namespace teleop::experiment {
namespace {

std::string mm(double m) { return format_number("%.1f", 1000.0 * m); }

std::string trace_csv(const std::vector<SafetyMarginResult>& cases) {
  std::ostringstream out;
  out << "case,activation_m,t_s,twin_margin_m,physical_margin_m,arms_m\n";
  for (const SafetyMarginResult& r : cases) {
    const SafetyMarginTrace& t = r.trace;
    for (size_t k = 0; k < t.t_s.size(); ++k) {
      out << r.config.name << ',' << format_number("%.4g", r.config.activation_m) << ','
          << format_number("%.3f", t.t_s[k]) << ',' << format_number("%.6f", t.twin_margin_m[k]) << ','
          << format_number("%.6f", t.physical_margin_m[k]) << ',' << format_number("%.6f", t.arms_m[k]) << '\n';
    }
  }
  return out.str();
}

}  // namespace

SafetyMarginScenario load_safety_margin_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("safety_margin_study");
  SafetyMarginScenario c;
  c.name = s.get_string("name");
  c.model_path = sim::get_model_path(s, "model");
  c.keyframe = s.get_string("keyframe", c.keyframe);
  c.sphere_radius_m = s.get_double("sphere_radius_m", Range{0.005, 0.5}, c.sphere_radius_m);
  c.coupling_stiffness_nm_per_rad = s.get_double("coupling_stiffness_nm_per_rad", Range{1, 1e5}, c.coupling_stiffness_nm_per_rad);
  c.coupling_damping_nms_per_rad = s.get_double("coupling_damping_nms_per_rad", Range{0, 1e4}, c.coupling_damping_nms_per_rad);
  c.feedback_gain = s.get_double("feedback_gain", Range{0, 10}, c.feedback_gain);
  c.lowpass_hz = s.get_double("lowpass_hz", Range{0, 1000}, c.lowpass_hz);
  c.push_n = s.get_double("push_n", Range{0, 200}, c.push_n);
  c.operator_damping_nms_per_rad = s.get_double("operator_damping_nms_per_rad", Range{0, 100}, c.operator_damping_nms_per_rad);
  c.duration_s = s.get_double("duration_s", Range{0.1, 60}, c.duration_s);
  c.rest_window_s = s.get_double("rest_window_s", Range{0.01, 60}, c.rest_window_s);
  if (c.rest_window_s >= c.duration_s) throw s.error("rest_window_s", "must be shorter than duration_s");
  c.trace_period_s = s.get_double("trace_period_s", Range{0.001, 1}, c.trace_period_s);
  c.cases.clear();
  std::set<std::string> names;
  for (const ConfigNode& k : s.get_node_list("cases")) {
    SafetyMarginCase sc{k.get_string("name"), k.get_double("activation_m", Range{0, 0.5})};
    if (!names.insert(sc.name).second) throw k.error("name", "'" + sc.name + "' is a second case of that name");
    c.cases.push_back(sc);
  }
  if (c.cases.empty()) throw s.error("cases", "lists no case");
  root.check_all_used();
  return c;
}

std::string format_safety_margin_markdown(const SafetyMarginScenario& s, const std::vector<SafetyMarginResult>& cases) {
  std::ostringstream out;
  out << "# " << s.name << ": PARTI Fig. 5, two hands driven into each other\n\n"
      << "Operator " << format_number("%g", s.push_n) << " N on each hand towards the other, margin spheres r = "
      << format_number("%g", 1000 * s.sphere_radius_m) << " mm around both end effectors (twin only), K = "
      << format_number("%g", s.coupling_stiffness_nm_per_rad) << " Nm/rad, D = "
      << format_number("%g", s.coupling_damping_nms_per_rad) << " Nms/rad, lambda = " << format_number("%g", s.feedback_gain)
      << ", " << format_number("%g", s.lowpass_hz) << " Hz low-pass, " << format_number("%g", s.duration_s)
      << " s; at rest: the mean over the last " << format_number("%g", s.rest_window_s) << " s.\n\n"
      << "| case | activation [mm] | twin margin min [mm] | twin margin at rest [mm] | physical margin min [mm] "
         "| physical margin at rest [mm] | arms' own geometry min [mm] | MuJoCo warnings |\n"
      << "|---|---|---|---|---|---|---|---|\n"
      << "| PARTI Fig. 5 (real PARTI) | – | ≥ 0 | ≥ 0 | – | – | > 0 (no collision) | – |\n";
  for (const SafetyMarginResult& r : cases) {
    out << "| " << r.config.name << " | " << mm(r.config.activation_m) << " | " << mm(r.min_twin_margin_m) << " | "
        << mm(r.rest_twin_margin_m) << " | " << mm(r.min_physical_margin_m) << " | " << mm(r.rest_physical_margin_m)
        << " | " << mm(r.min_arms_m) << " | " << r.warnings << " |\n";
  }
  out << "\nTwin margin: the distance between the twin's margin spheres (what Fig. 5 plots: the twin's "
         "collision meshes). Physical margin: the same spheres carried on the operated robot's own "
         "kinematics. Arms' own geometry: the physical robot's links 5-7 of one arm against the other's. "
         "Negative: penetration.\n";
  return out.str();
}

SafetyMarginStudyResult run_safety_margin_study(const SafetyMarginScenario& s, const std::string& out_dir, bool plots) {
  SafetyMarginStudyResult result;
  for (const SafetyMarginCase& c : s.cases) result.cases.push_back(run_safety_margin_case(s, c, s.feedback_gain));
  result.out_dir = make_report_dir(out_dir, "teleop-" + s.name + "-");
  const std::filesystem::path dir(result.out_dir);
  result.trace_csv = (dir / (s.name + "_trace.csv")).string();
  result.markdown = (dir / (s.name + ".md")).string();
  write_text(result.trace_csv, trace_csv(result.cases));
  write_text(result.markdown, format_safety_margin_markdown(s, result.cases));
  if (plots) {
    try {
      plot_parti_study(find_plot_tool(), "margins", result.trace_csv, result.out_dir);
    } catch (const PlotError& e) {
      result.plot_error = e.what();
    }
  }
  return result;
}

}  // namespace teleop::experiment
