// One run of the SVH hand study: its samples and their analysis (MAD, tip force).
#include "teleop/experiment/hand_study.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "teleop/experiment/hand_study_simulation.h"
#include "teleop/experiment/metrics.h"

namespace teleop::experiment {
namespace {

// qpos addresses of hand_study_joints() in the model
std::vector<int> study_qpos(const hand::HandPlant& plant) {
  std::vector<int> out;
  for (const std::string& name : hand_study_joints()) out.push_back(plant.mujoco().joint_qpos_address(name));
  return out;
}

int steps_per_sample(const HandStudyConfig& c, double timestep_s) {
  const long steps = std::lround(c.sample_period_s / timestep_s);
  if (steps < 1 || std::abs(static_cast<double>(steps) * timestep_s - c.sample_period_s) > 1e-9) {
    throw std::runtime_error(c.file + ": sample_period_s " + std::to_string(c.sample_period_s) +
                             " is no multiple of the model's timestep " + std::to_string(timestep_s));
  }
  return static_cast<int>(steps);
}

// MAD per joint and the force statistics over the recording window
void analyse(const HandStudyConfig& c, HandStudyRunResult& r) {
  const Window window{r.record_begin_s, r.t_s.back()};
  double paper_sum = 0.0;
  for (size_t j = 0; j < r.q_rad.size(); ++j) {
    r.mad_rad.push_back(mean_absolute_deviation_in(r.t_s, r.q_rad[j], c.mad_window, window));
    if (j < kPaperTableJoints) paper_sum += r.mad_rad.back();
    r.mad_max_rad = std::max(r.mad_max_rad, r.mad_rad.back());
  }
  r.mad_paper_average_rad = paper_sum / static_cast<double>(kPaperTableJoints);
  r.tip_force_mean_n = mean_in(r.t_s, r.tip_force_n, window);
  r.tip_force_sd_n = std::sqrt(
      std::max(0.0, std::pow(rms_in(r.t_s, r.tip_force_n, window), 2) - r.tip_force_mean_n * r.tip_force_mean_n));
  r.tip_force_min_n = std::numeric_limits<double>::infinity();
  r.tip_force_max_n = -std::numeric_limits<double>::infinity();
  r.first_contact_s = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < r.t_s.size(); ++i) {
    if (r.tip_force_n[i] > 0.0 && std::isnan(r.first_contact_s)) r.first_contact_s = r.t_s[i];
    if (!window.contains(r.t_s[i])) continue;
    r.tip_force_min_n = std::min(r.tip_force_min_n, r.tip_force_n[i]);
    r.tip_force_max_n = std::max(r.tip_force_max_n, r.tip_force_n[i]);
  }
}

}  // namespace

const std::vector<std::string>& hand_study_joints() {
  static const std::vector<std::string> joints = [] {
    // Tables II and III of the paper, in their order
    std::vector<std::string> out = {"Finger_Spread",        "Index_Finger_Distal",    "Index_Finger_Proximal",
                                    "Middle_Finger_Distal", "Middle_Finger_Proximal", "Pinky",
                                    "Ring_Finger",          "Thumb_Flexion",          "Thumb_Opposition",
                                    "shoulder_lift_joint",  "shoulder_pan_joint",     "elbow_joint",
                                    "wrist_1_joint",        "wrist_2_joint",          "wrist_3_joint"};
    // then the joints the mechanism moves, which the paper does not list
    for (const std::string_view name : hand::kHandJointNames) {
      if (std::find(hand::kHandMotorNames.begin(), hand::kHandMotorNames.end(), name) == hand::kHandMotorNames.end()) {
        out.emplace_back(name);
      }
    }
    return out;
  }();
  return joints;
}

HandStudyRunResult run_hand_study_case(const HandStudyConfig& c, const HandStudyRun& run) {
  const auto wall_start = std::chrono::steady_clock::now();
  HandStudySimulation simulation(c, run);
  const hand::HandPlant& plant = simulation.plant();
  const mjData* d = plant.data();
  const int sample_every = steps_per_sample(c, plant.model()->opt.timestep);
  const long steps = std::lround((simulation.motion_s() + c.settle_s + c.record_s) / plant.model()->opt.timestep);
  const std::vector<int> qpos = study_qpos(plant);

  HandStudyRunResult r;
  r.run = run;
  r.record_begin_s = simulation.motion_s() + c.settle_s;
  r.q_rad.assign(qpos.size(), {});
  for (long step = 1; step <= steps; ++step) {
    simulation.step();
    r.coupling_residual_max_rad = std::max(r.coupling_residual_max_rad, plant.coupling_residual_rad());
    if (simulation.foreign_contact()) ++r.foreign_contact_steps;
    if (step % sample_every != 0) continue;
    r.t_s.push_back(simulation.time_s());
    for (size_t j = 0; j < qpos.size(); ++j) r.q_rad[j].push_back(d->qpos[qpos[j]]);
    r.tip_force_n.push_back(plant.tip_force_n());
  }
  r.mujoco_warnings = plant.mujoco_warnings();
  analyse(c, r);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return r;
}

}  // namespace teleop::experiment
