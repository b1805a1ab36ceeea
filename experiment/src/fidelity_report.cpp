// The fidelity study's outputs: its CSVs, the Markdown report in the shape of the thesis's Tables
// 4.1 and 4.2 with its numbers beside ours, and the figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "report_files.h"
#include "teleop/experiment/fidelity_study.h"
#include "teleop/experiment/plots.h"

namespace teleop::experiment {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The thesis's numbers (shared/papers/justin-controller-simulation-coupling.md), in the column
// order of its tables: state space poses, joint impedance poses, state space movements, joint
// impedance movements. NaN: the thesis gives none.
struct ThesisRow {
  const char* label;
  std::array<double, 4> values;
};
// Table 4.1, joint positions (RMSE of errors in degrees; max error in degrees)
constexpr std::array<ThesisRow, 6> kTable41 = {{
    {"Arm Mean RMSE", {0.0568, 0.252, 0.0742, 0.227}},
    {"Arm Max RMSE", {0.0627, 0.277, 0.153, 0.319}},
    {"Arm Max Error [°]", {0.162, 0.673, 0.321, 0.797}},
    {"Torso Mean RMSE", {0.0362, 0.319, 0.0469, 0.330}},
    {"Torso Max RMSE", {0.0622, 0.468, 0.155, 0.836}},
    {"Torso Max Error [°]", {0.107, 0.744, 0.267, 1.413}},
}};
// Table 4.2, joint torques (RMSE of errors in N m; max error in N m)
constexpr std::array<ThesisRow, 6> kTable42 = {{
    {"Arm Mean RMSE", {1.223, 1.199, 1.320, 1.250}},
    {"Arm Max RMSE", {1.653, 1.598, 2.441, 2.065}},
    {"Arm Max Error [N m]", {3.293, 3.210, 6.245, 5.091}},
    {"Torso Mean RMSE", {2.057, 2.044, 2.257, 2.454}},
    {"Torso Max RMSE", {2.911, 2.267, 7.375, 7.710}},
    {"Torso Max Error [N m]", {3.928, 3.009, 11.644, 11.977}},
}};
// §4.3.2, the end effectors by forward kinematics (Fig. 4.9): position [cm] and rotation (eq. 4.5)
constexpr std::array<ThesisRow, 4> kEndEffector = {{
    {"Mean position error [cm]", {0.171, 0.568, 0.171, 0.601}},
    {"Max position error [cm]", {kNaN, kNaN, 1.01, 1.89}},
    {"Mean rotation θ", {0.00597, 0.0152, kNaN, kNaN}},
    {"Max rotation θ", {kNaN, 0.0229, kNaN, kNaN}},
}};
// §4.5: the real-time factor without contacts, with the wiper on the panel, wiping across it
constexpr double kThesisRtfFree = 0.86;
constexpr double kThesisRtfContact = 0.49;
constexpr double kThesisRtfWiping = 0.14;

std::string format(const char* spec, double v) {
  if (std::isnan(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, v);
  return buf;
}

// a CSV cell: NaN as "nan" (what a CSV reader parses), not the tables' dash
std::string csv_number(const char* spec, double v) { return std::isnan(v) ? std::string("nan") : format(spec, v); }

// ours: three significant digits; the thesis's: as printed (up to five)
std::string sig3(double v) { return format("%.3g", v); }
std::string thesis_text(double v) { return format("%.5g", v); }

// the four columns of the thesis's tables: (controller, movements)
constexpr std::array<std::pair<FidelityController, bool>, 4> kColumns = {{
    {FidelityController::kStateSpace, false},
    {FidelityController::kJointImpedance, false},
    {FidelityController::kStateSpace, true},
    {FidelityController::kJointImpedance, true},
}};
constexpr std::array<const char*, 4> kColumnTitles = {"State space, poses", "Joint imp., poses",
                                                      "State space, movements", "Joint imp., movements"};

// one cell of ours: the value of each seed's run, as "mean (min–max)" over the seeds
std::string spread_cell(const std::vector<double>& values) {
  if (values.empty()) return "–";
  double lo = values.front();
  double hi = values.front();
  double sum = 0.0;
  for (const double v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
  }
  const double mean = sum / static_cast<double>(values.size());
  if (values.size() == 1) return sig3(mean);
  return sig3(mean) + " (" + sig3(lo) + "–" + sig3(hi) + ")";
}

// the table runs of one controller, one per seed
std::vector<const FidelityRun*> table_runs(const std::vector<FidelityRun>& runs, FidelityController controller) {
  std::vector<const FidelityRun*> out;
  for (const FidelityRun& r : runs) {
    if (!r.contact && r.controller == controller) out.push_back(&r);
  }
  return out;
}

using CellValue = double (*)(const FidelityCell&);

// a table in the thesis's shape: per row our spread over the seeds, then the thesis's value
std::string paper_table(const std::vector<FidelityRun>& runs,
                        const std::vector<std::pair<const ThesisRow*, CellValue>>& rows) {
  std::string out = "| |";
  std::string rule = "|---|";
  for (const char* title : kColumnTitles) {
    out += std::string(" ") + title + ": ours | thesis |";
    rule += "---|---|";
  }
  out += "\n" + rule + "\n";
  for (const auto& [thesis, value] : rows) {
    out += std::string("| ") + thesis->label + " |";
    for (size_t col = 0; col < kColumns.size(); ++col) {
      std::vector<double> ours;
      if (value != nullptr) {
        for (const FidelityRun* r : table_runs(runs, kColumns[col].first)) {
          ours.push_back(value(aggregate(*r, kColumns[col].second)));
        }
      }
      out += " " + (value != nullptr ? spread_cell(ours) : std::string("no torso")) + " | " +
             thesis_text(thesis->values[col]) + " |";
    }
    out += "\n";
  }
  return out;
}

std::vector<uint64_t> seeds_of(const std::vector<FidelityRun>& runs) {
  std::vector<uint64_t> seeds;
  for (const FidelityRun& r : runs) {
    if (std::find(seeds.begin(), seeds.end(), r.seed) == seeds.end()) seeds.push_back(r.seed);
  }
  return seeds;
}

std::string real_time_table(const std::vector<FidelityRun>& runs) {
  std::vector<double> free;
  std::vector<double> contact;
  for (const FidelityRun& r : runs) {
    if (!std::isnan(r.rt_factor_free)) free.push_back(r.rt_factor_free);
    if (!std::isnan(r.rt_factor_contact)) contact.push_back(r.rt_factor_contact);
  }
  const auto cell = [](const std::vector<double>& v) {
    if (v.empty()) return std::string("– (no such step)");
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    double sum = 0.0;
    for (const double x : v) sum += x;
    return format("%.1f", sum / static_cast<double>(v.size())) + " (" + format("%.1f", *lo) + "–" +
           format("%.1f", *hi) + ")";
  };
  return "| | ours: replay (lock-step, in process) | thesis: Gazebo + Simulink (lock-step) |\n|---|---|---|\n"
         "| free motion | " +
         cell(free) + " | " + format("%.2f", kThesisRtfFree) + " |\n| in contact | " + cell(contact) + " | " +
         format("%.2f", kThesisRtfContact) + " (wiping across: " + format("%.2f", kThesisRtfWiping) + ") |\n";
}

std::string segments_table(const std::vector<FidelityRun>& runs, bool contact, uint64_t seed) {
  std::string out =
      "| controller | pose / movement | q RMSE mean | sd | max | max joint [°] | τ RMSE mean [N m] | sd | max | max "
      "joint [N m] | ee mean [cm] | ee max [cm] | θ mean | θ max |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const FidelityRun& r : runs) {
    if (r.contact != contact || r.seed != seed) continue;
    for (const FidelitySegment& g : r.segments) {
      out += std::string("| ") + controller_name(r.controller) + " | " + g.name + " | " +
             format("%.4f", g.q_rmse_deg.mean) + " | " + format("%.4f", g.q_rmse_deg.sd) + " | " +
             format("%.4f", g.q_rmse_deg.max) + " | " + format("%.4f", g.q_max_joint_deg) + " | " +
             format("%.3f", g.tau_rmse_nm.mean) + " | " + format("%.3f", g.tau_rmse_nm.sd) + " | " +
             format("%.3f", g.tau_rmse_nm.max) + " | " + format("%.3f", g.tau_max_joint_nm) + " | " +
             format("%.4f", g.ee_position_cm.mean) + " | " + format("%.4f", g.ee_position_cm.max) + " | " +
             format("%.2e", g.ee_rotation.mean) + " | " + format("%.2e", g.ee_rotation.max) + " |\n";
    }
  }
  return out;
}

std::string robots_table(const std::vector<FidelityRun>& runs) {
  std::string out =
      "| seed | links' mass [kg] | mass factors | friction factors | damping added [N m s/rad] | armature factors "
      "|\n|---|---|---|---|---|---|\n";
  const auto list = [](const std::vector<double>& v, const char* spec) {
    std::string s;
    for (const double x : v) s += (s.empty() ? "" : ", ") + format(spec, x);
    return s;
  };
  std::vector<uint64_t> done;
  for (const FidelityRun& r : runs) {
    if (std::find(done.begin(), done.end(), r.seed) != done.end()) continue;
    done.push_back(r.seed);
    const sim::AppliedPerturbation& p = r.perturbation;
    out += "| " + std::to_string(r.seed) + " | " + format("%.2f", p.perturbed_mass_kg) + " (model " +
           format("%.2f", p.nominal_mass_kg) + ") | " + list(p.mass_factor, "%.3f") + " | " +
           list(p.friction_factor, "%.2f") + " | " + list(p.damping_nms_per_rad, "%.2f") + " | " +
           list(p.armature_factor, "%.2f") + " |\n";
  }
  return out;
}

std::string summary_fields(const Summary& s) {
  return csv_number("%.6g", s.mean) + "," + csv_number("%.6g", s.sd) + "," + csv_number("%.6g", s.max);
}

std::string segments_csv(const std::vector<FidelityRun>& runs) {
  std::string out =
      "sequence,contact,controller,seed,segment,kind,begin_s,end_s,q_rmse_deg_mean,q_rmse_deg_sd,q_rmse_deg_max,"
      "q_max_joint_deg,tau_rmse_nm_mean,tau_rmse_nm_sd,tau_rmse_nm_max,tau_max_joint_nm,ee_position_cm_mean,"
      "ee_position_cm_sd,ee_position_cm_max,ee_rotation_mean,ee_rotation_sd,ee_rotation_max\n";
  for (const FidelityRun& r : runs) {
    for (const FidelitySegment& g : r.segments) {
      out += r.sequence + "," + (r.contact ? "yes" : "no") + "," + controller_name(r.controller) + "," +
             std::to_string(r.seed) + "," + g.name + "," + (g.movement ? "movement" : "pose") + "," +
             csv_number("%.3f", g.window.begin_s) + "," + csv_number("%.3f", g.window.end_s) + "," +
             summary_fields(g.q_rmse_deg) + "," + csv_number("%.6g", g.q_max_joint_deg) + "," +
             summary_fields(g.tau_rmse_nm) + "," + csv_number("%.6g", g.tau_max_joint_nm) + "," +
             summary_fields(g.ee_position_cm) + "," + summary_fields(g.ee_rotation) + "\n";
    }
  }
  return out;
}

std::string runs_csv(const std::vector<FidelityRun>& runs) {
  std::string out =
      "sequence,controller,seed,contact,steps,contact_steps,rt_factor_free,rt_factor_contact,mujoco_warnings,"
      "link_mass_kg,nominal_link_mass_kg\n";
  for (const FidelityRun& r : runs) {
    out += r.sequence + "," + controller_name(r.controller) + "," + std::to_string(r.seed) + "," +
           (r.contact ? "yes" : "no") + "," + std::to_string(r.free_steps + r.contact_steps) + "," +
           std::to_string(r.contact_steps) + "," + csv_number("%.4g", r.rt_factor_free) + "," +
           csv_number("%.4g", r.rt_factor_contact) + "," + std::to_string(r.mujoco_warnings) + "," +
           csv_number("%.6f", r.perturbation.perturbed_mass_kg) + "," +
           csv_number("%.6f", r.perturbation.nominal_mass_kg) + "\n";
  }
  return out;
}

// the signals every `period_s` (the figures' input; the metrics use every step)
std::string trace_csv(const std::vector<FidelityRun>& runs, double period_s) {
  std::string out =
      "sequence,controller,seed,t_s,q_rmse_deg,q_max_joint_deg,tau_rmse_nm,tau_max_joint_nm,ee_position_cm,"
      "ee_rotation\n";
  for (const FidelityRun& r : runs) {
    const FidelitySignals& s = r.signals;
    if (s.t_s.size() < 2) continue;
    const auto every = std::max<size_t>(1, static_cast<size_t>(std::lround(period_s / (s.t_s[1] - s.t_s[0]))));
    for (size_t k = every - 1; k < s.t_s.size(); k += every) {
      out += r.sequence + "," + controller_name(r.controller) + "," + std::to_string(r.seed) + "," +
             csv_number("%.3f", s.t_s[k]) + "," + csv_number("%.6g", s.q_rmse_deg[k]) + "," +
             csv_number("%.6g", s.q_max_joint_deg[k]) + "," + csv_number("%.6g", s.tau_rmse_nm[k]) + "," +
             csv_number("%.6g", s.tau_max_joint_nm[k]) + "," + csv_number("%.6g", s.ee_position_cm[k]) + "," +
             csv_number("%.6g", s.ee_rotation[k]) + "\n";
    }
  }
  return out;
}

}  // namespace

bool FidelityStudyResult::sound() const {
  return std::all_of(runs.begin(), runs.end(), [](const FidelityRun& r) { return r.mujoco_warnings == 0; });
}

std::string format_fidelity_markdown(const FidelityStudyConfig& c, const std::vector<FidelityRun>& runs) {
  const std::vector<uint64_t> seeds = seeds_of(runs);
  std::string seed_text;
  for (const uint64_t s : seeds) seed_text += (seed_text.empty() ? "" : ", ") + std::to_string(s);
  std::string out = "# Fidelity study: " + c.name + "\n\n";
  out += "A \"real\" Panda-class arm (the nominal model with link masses ±" +
         format("%g", 100 * c.perturbation.mass_fraction) + " %, centres of mass ±" +
         format("%g", 100 * c.perturbation.com_offset_m) + " cm, dry friction ±" +
         format("%g", 100 * c.perturbation.friction_fraction) + " %, viscous damping 0–" +
         format("%g", c.perturbation.damping_max_nms_per_rad) + " N m s/rad, rotor inertia ±" +
         format("%g", 100 * c.perturbation.armature_fraction) + " %; sensor noise σ " +
         format("%g", c.sensor_noise.q_rad) + " rad, " + format("%g", c.sensor_noise.dq_radps) + " rad/s, " +
         format("%g", c.sensor_noise.tau_nm) +
         " N m) runs each controller through the poses; its commands are replayed in lock-step into the nominal "
         "model, the same controller code driving both. Minimum-jerk movements of " +
         format("%g", c.move_s) + " s, " + format("%g", c.hold_s) + " s at each pose; a pose's metrics over the last " +
         format("%g", c.pose_window_s) + " s of its hold, a movement's from " + format("%g", c.movement_before_s) +
         " s before to " + format("%g", c.movement_after_s) +
         " s after it. Ours: the mean over the \"real\" robots of seeds " + seed_text +
         " (range in brackets); thesis: Rollin' Justin against Gazebo (its arms; it also lists the torso, which this "
         "arm does not have).\n";
  const std::vector<std::pair<const ThesisRow*, CellValue>> positions = {
      {&kTable41[0], [](const FidelityCell& x) { return x.q_rmse_deg.mean; }},
      {&kTable41[1], [](const FidelityCell& x) { return x.q_rmse_deg.max; }},
      {&kTable41[2], [](const FidelityCell& x) { return x.q_max_joint_deg; }},
      {&kTable41[3], nullptr},
      {&kTable41[4], nullptr},
      {&kTable41[5], nullptr},
  };
  out += "\n## Table 4.1: joint positions, RMSE of the errors in degrees (eq. 4.2)\n\n" + paper_table(runs, positions);
  const std::vector<std::pair<const ThesisRow*, CellValue>> torques = {
      {&kTable42[0], [](const FidelityCell& x) { return x.tau_rmse_nm.mean; }},
      {&kTable42[1], [](const FidelityCell& x) { return x.tau_rmse_nm.max; }},
      {&kTable42[2], [](const FidelityCell& x) { return x.tau_max_joint_nm; }},
      {&kTable42[3], nullptr},
      {&kTable42[4], nullptr},
      {&kTable42[5], nullptr},
  };
  out += "\n## Table 4.2: joint torques, RMSE of the errors in N m (eq. 4.2)\n\n" + paper_table(runs, torques);
  const std::vector<std::pair<const ThesisRow*, CellValue>> end_effector = {
      {&kEndEffector[0], [](const FidelityCell& x) { return x.ee_position_cm.mean; }},
      {&kEndEffector[1], [](const FidelityCell& x) { return x.ee_position_cm.max; }},
      {&kEndEffector[2], [](const FidelityCell& x) { return x.ee_rotation.mean; }},
      {&kEndEffector[3], [](const FidelityCell& x) { return x.ee_rotation.max; }},
  };
  out += "\n## End effector (§4.3.2): position error in cm (eq. 4.4), rotation distance θ (eq. 4.5)\n\n" +
         paper_table(runs, end_effector) + "\nθ of a 1° rotation is 0.0247. Thesis: \"–\" where it gives no number.\n";
  out += "\n## Real-time factor (§4.5): simulated over computing time\n\n" + real_time_table(runs);
  out += "\n## Per pose and movement, seed " + std::to_string(seeds.front()) + "\n\n" +
         segments_table(runs, false, seeds.front());
  const bool any_contact = std::any_of(runs.begin(), runs.end(), [](const FidelityRun& r) { return r.contact; });
  if (any_contact) {
    out += "\n## In contact (not in the thesis's tables), seed " + std::to_string(seeds.front()) + "\n\n" +
           segments_table(runs, true, seeds.front());
  }
  out += "\n## The \"real\" robots (per joint 1–7)\n\n" + robots_table(runs);
  return out;
}

FidelityStudyResult run_fidelity_study(const FidelityStudyConfig& config, const FidelityStudyOptions& options) {
  for (const std::string& name : options.sequences) {
    const auto known = [&](const FidelitySequence& s) { return s.name == name; };
    if (std::none_of(config.sequences.begin(), config.sequences.end(), known)) {
      throw std::runtime_error(config.file + " has no sequence '" + name + "'");
    }
  }
  const std::vector<uint64_t>& seeds = options.seeds.empty() ? config.seeds : options.seeds;
  FidelityStudyResult result;
  for (const FidelitySequence& sequence : config.sequences) {
    const bool chosen = options.sequences.empty() || std::find(options.sequences.begin(), options.sequences.end(),
                                                               sequence.name) != options.sequences.end();
    if (!chosen) continue;
    for (const FidelityController controller : {FidelityController::kStateSpace, FidelityController::kJointImpedance}) {
      for (const uint64_t seed : seeds) result.runs.push_back(run_fidelity_case(config, sequence, controller, seed));
    }
  }
  result.out_dir = make_report_dir(options.out_dir, "teleop-fidelity-" + config.name + "-");
  const std::filesystem::path dir(result.out_dir);
  result.segments_csv = (dir / (config.name + "_segments.csv")).string();
  result.runs_csv = (dir / (config.name + "_runs.csv")).string();
  result.trace_csv = (dir / (config.name + "_trace.csv")).string();
  result.markdown = (dir / (config.name + ".md")).string();
  write_text(result.segments_csv, segments_csv(result.runs));
  write_text(result.runs_csv, runs_csv(result.runs));
  write_text(result.trace_csv, trace_csv(result.runs, config.trace_period_s));
  write_text(result.markdown, format_fidelity_markdown(config, result.runs));
  if (options.plots) {
    try {
      plot_fidelity_study(find_plot_tool(), result.trace_csv, result.segments_csv, result.out_dir);
    } catch (const PlotError& e) {
      result.plot_error = e.what();
    }
  }
  return result;
}

}  // namespace teleop::experiment
