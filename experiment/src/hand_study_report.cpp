// The hand study's outputs: its CSVs, the Markdown report beside the paper's tables, the figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "hand_study_paper.h"
#include "report_files.h"
#include "teleop/experiment/hand_study.h"
#include "teleop/experiment/plots.h"

namespace teleop::experiment {
namespace {

std::string format(const char* spec, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, v);
  return buf;
}

// a MAD as the tables print it: 0 exactly, else three significant digits
std::string mad_text(double v) {
  if (std::isnan(v)) return "n/a";
  return v == 0.0 ? "0" : format("%.3e", v);
}

std::string coupling_name(hand::CouplingMode mode) {
  return mode == hand::CouplingMode::kServo ? "servo" : "constraint";
}

std::string inertia_text(double inertia_kgm2) { return inertia_kgm2 > 0.0 ? format("%g", inertia_kgm2) : "model"; }

std::string contact_text(const HandStudyConfig& c) {
  if (c.friction_cone.empty() && c.noslip_iterations < 0) return "the model's solver options";
  return (c.friction_cone.empty() ? std::string("the model's") : c.friction_cone) + " friction cones, " +
         (c.noslip_iterations < 0 ? std::string("the model's") : std::to_string(c.noslip_iterations)) +
         " no-slip iterations";
}

// "ours @ 0.01 kg m^2" and the like, as a column title
std::string run_title(const HandStudyRunResult& r) {
  const std::string inertia =
      r.run.link_inertia_kgm2 > 0.0 ? inertia_text(r.run.link_inertia_kgm2) + " kg m²" : "model's";
  return r.run.name + " (" + inertia + ")";
}

// Table II/III's shape: the paper's 15 joints and its average, our runs of one coupling mode,
// then the paper's Gazebo and MuJoCo columns
std::string paper_shaped_table(const std::vector<const HandStudyRunResult*>& runs) {
  std::string out = "| Joint |";
  std::string rule = "|---|";
  for (const HandStudyRunResult* r : runs) {
    out += " " + run_title(*r) + " |";
    rule += "---|";
  }
  for (const double inertia : kPaperInertiasKgm2) {
    out += " paper, Gazebo (" + format("%g", inertia) + " kg m²) |";
    rule += "---|";
  }
  out += " paper, MuJoCo (0.1 kg m²) |\n" + rule + "---|\n";
  const auto row = [&](const PaperMadRow& paper, size_t joint, bool average) {
    out += "| " + (average ? std::string("**Average**") : "\"" + std::string(paper.joint) + "\"") + " |";
    for (const HandStudyRunResult* r : runs)
      out += " " + mad_text(average ? r->mad_paper_average_rad : r->mad_rad[joint]) + " |";
    for (const double v : paper.gazebo_rad) out += " " + mad_text(v) + " |";
    out += " " + mad_text(paper.mujoco_rad) + " |\n";
  };
  for (size_t j = 0; j < kPaperTableJoints; ++j) row(paper_mad_rows()[j], j, false);
  row(paper_mad_average(), 0, true);
  return out;
}

std::string coupled_joints_table(const std::vector<HandStudyRunResult>& runs) {
  std::string out = "| Joint |";
  std::string rule = "|---|";
  for (const HandStudyRunResult& r : runs) {
    out += " " + r.run.name + " |";
    rule += "---|";
  }
  out += "\n" + rule + "\n";
  for (size_t j = kPaperTableJoints; j < hand_study_joints().size(); ++j) {
    out += "| \"" + hand_study_joints()[j] + "\" |";
    for (const HandStudyRunResult& r : runs) out += " " + mad_text(r.mad_rad[j]) + " |";
    out += "\n";
  }
  return out;
}

std::string runs_table(const std::vector<HandStudyRunResult>& runs) {
  std::string out =
      "| run | link inertia [kg m²] | couplings | MAD average, paper's 15 [rad] | MAD max, all 26 [rad] | "
      "tip force mean [N] | sd [N] | min–max [N] | first contact [s] | coupling residual max [rad] | MuJoCo "
      "warnings | steps with another contact | computing [s] "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const HandStudyRunResult& r : runs) {
    out += "| " + r.run.name + " | " + inertia_text(r.run.link_inertia_kgm2) + " | " + coupling_name(r.run.coupling) +
           " | " + mad_text(r.mad_paper_average_rad) + " | " + mad_text(r.mad_max_rad) + " | " +
           format("%.4f", r.tip_force_mean_n) + " | " + format("%.2e", r.tip_force_sd_n) + " | " +
           format("%.4f", r.tip_force_min_n) + "–" + format("%.4f", r.tip_force_max_n) + " | " +
           format("%.3f", r.first_contact_s) + " | " + format("%.2e", r.coupling_residual_max_rad) + " | " +
           std::to_string(r.mujoco_warnings) + " | " + std::to_string(r.foreign_contact_steps) + " | " +
           format("%.2f", r.wall_s) + " |\n";
  }
  return out;
}

std::string mad_csv(const std::vector<HandStudyRunResult>& runs) {
  std::string out = "run,link_inertia_kgm2,couplings,joint,in_paper_tables,mad_rad\n";
  for (const HandStudyRunResult& r : runs) {
    for (size_t j = 0; j < r.mad_rad.size(); ++j) {
      out += r.run.name + "," + inertia_text(r.run.link_inertia_kgm2) + "," + coupling_name(r.run.coupling) + "," +
             hand_study_joints()[j] + "," + (j < kPaperTableJoints ? "yes" : "no") + "," +
             format("%.6e", r.mad_rad[j]) + "\n";
    }
  }
  return out;
}

std::string runs_csv(const std::vector<HandStudyRunResult>& runs) {
  std::string out =
      "run,link_inertia_kgm2,couplings,mad_paper_average_rad,mad_max_rad,tip_force_mean_n,tip_force_sd_n,"
      "tip_force_min_n,tip_force_max_n,first_contact_s,coupling_residual_max_rad,mujoco_warnings,"
      "foreign_contact_steps,sound,wall_s\n";
  for (const HandStudyRunResult& r : runs) {
    out += r.run.name + "," + inertia_text(r.run.link_inertia_kgm2) + "," + coupling_name(r.run.coupling) + "," +
           format("%.6e", r.mad_paper_average_rad) + "," + format("%.6e", r.mad_max_rad) + "," +
           format("%.9g", r.tip_force_mean_n) + "," + format("%.6e", r.tip_force_sd_n) + "," +
           format("%.9g", r.tip_force_min_n) + "," + format("%.9g", r.tip_force_max_n) + "," +
           format("%.3f", r.first_contact_s) + "," + format("%.6e", r.coupling_residual_max_rad) + "," +
           std::to_string(r.mujoco_warnings) + "," + std::to_string(r.foreign_contact_steps) + "," +
           (r.sound() ? "yes" : "no") + "," + format("%.3f", r.wall_s) + "\n";
  }
  return out;
}

// every sample of every run, joints at full precision: a MAD of 1e-17 rad must survive the file
std::string trace_csv(const std::vector<HandStudyRunResult>& runs) {
  std::string out = "run,t_s,recording,tip_force_n";
  for (const std::string& joint : hand_study_joints()) out += "," + joint;
  out += "\n";
  for (const HandStudyRunResult& r : runs) {
    for (size_t i = 0; i < r.t_s.size(); ++i) {
      out += r.run.name + "," + format("%.3f", r.t_s[i]) + "," + (r.t_s[i] >= r.record_begin_s ? "1" : "0") + "," +
             format("%.9g", r.tip_force_n[i]);
      for (const std::vector<double>& q : r.q_rad) out += "," + format("%.17g", q[i]);
      out += "\n";
    }
  }
  return out;
}

}  // namespace

std::string format_hand_study_markdown(const HandStudyConfig& c, const std::vector<HandStudyRunResult>& runs) {
  std::string out = "# Hand study: " + c.name + "\n\n";
  std::string path = "`" + c.path.front().keyframe + "`";
  for (size_t i = 1; i < c.path.size(); ++i) {
    path += " → `" + c.path[i].keyframe + "` (" + format("%g", c.path[i].move_s) + " s)";
  }
  out += "Model `" + c.model_path + "`; " + path + " on minimum-jerk joint motions, " + format("%g", c.settle_s) +
         " s to settle, then " + format("%g", c.record_s) + " s recorded at " + format("%g", 1.0 / c.sample_period_s) +
         " Hz; MAD (eq. 3) against the " + std::to_string(c.mad_window) +
         "-sample running mean over the recording. PD bandwidths: arm " + format("%g", c.arm_bandwidth_radps) +
         " rad/s, hand " + format("%g", c.hand_bandwidth_radps) + " rad/s, damping ratio " +
         format("%g", c.damping_ratio) + ", coupled-joint servos " + format("%g", c.servo_bandwidth_radps) +
         " rad/s; hand motors limited to " +
         (c.hand_torque_limit_nm > 0.0 ? format("%g", c.hand_torque_limit_nm) + " N m"
                                       : std::string("the model's torque")) +
         "; contact: " + contact_text(c) + ". Paper: Tables II (Gazebo) and III (MuJoCo).\n";
  for (const hand::CouplingMode mode : {hand::CouplingMode::kConstraint, hand::CouplingMode::kServo}) {
    std::vector<const HandStudyRunResult*> of_mode;
    for (const HandStudyRunResult& r : runs) {
      if (r.run.coupling == mode) of_mode.push_back(&r);
    }
    if (of_mode.empty()) continue;
    out += mode == hand::CouplingMode::kConstraint
               ? "\n## Joint MAD at rest in contact [rad], couplings as the mechanism (equalities)\n\n"
               : "\n## Joint MAD at rest in contact [rad], couplings as servos (equalities off)\n\n";
    out += paper_shaped_table(of_mode);
  }
  out += "\n## The coupled joints (not in the paper's tables), MAD [rad]\n\n" + coupled_joints_table(runs);
  out += "\n## Runs\n\n" + runs_table(runs);
  return out;
}

HandStudyResult run_hand_study(const HandStudyConfig& config, const HandStudyOptions& options) {
  HandStudyResult result;
  for (const std::string& name : options.runs) {
    const auto known = [&](const HandStudyRun& r) { return r.name == name; };
    if (std::none_of(config.runs.begin(), config.runs.end(), known)) {
      throw std::runtime_error(config.file + " has no run '" + name + "'");
    }
  }
  for (const HandStudyRun& run : config.runs) {
    const bool chosen =
        options.runs.empty() || std::find(options.runs.begin(), options.runs.end(), run.name) != options.runs.end();
    if (chosen) result.runs.push_back(run_hand_study_case(config, run));
  }
  result.out_dir = make_report_dir(options.out_dir, "teleop-hand-study-" + config.name + "-");
  const std::filesystem::path dir(result.out_dir);
  result.mad_csv = (dir / (config.name + "_mad.csv")).string();
  result.runs_csv = (dir / (config.name + "_runs.csv")).string();
  result.trace_csv = (dir / (config.name + "_trace.csv")).string();
  result.markdown = (dir / (config.name + ".md")).string();
  write_text(result.mad_csv, mad_csv(result.runs));
  write_text(result.runs_csv, runs_csv(result.runs));
  write_text(result.trace_csv, trace_csv(result.runs));
  write_text(result.markdown, format_hand_study_markdown(config, result.runs));
  if (options.plots) {
    try {
      plot_hand_study(find_plot_tool(), result.trace_csv, result.out_dir);
    } catch (const PlotError& e) {
      result.plot_error = e.what();
    }
  }
  return result;
}

}  // namespace teleop::experiment
