// teleop_twin_bench: the cost of one twin step (TwinSimulation::step_coupled plus the per-cycle
// observations the node publishes: contact wrench and distance of each configured pair) beside a
// bare mj_step on the same model, in the same run, for the single arm, the two-arm body and the
// wiping scene. Reports per-step cost percentiles, the real-time factor (model timestep over mean
// step cost) and the overhead ratio twin / bare. Rounds alternate between the two so that machine
// noise hits both alike. Results and the command: docs/twin.md.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "teleop/common/clock.h"
#include "teleop/twin/twin_simulation.h"

namespace {

using teleop::JointVector;
using teleop::twin::TwinModelConfig;
using teleop::twin::TwinSimulation;

struct Case {
  const char* name;
  TwinModelConfig config;
};

std::vector<Case> cases(const std::string& models) {
  TwinModelConfig arm;
  arm.model_path = models + "/panda.xml";
  arm.keyframe = "ready";
  TwinModelConfig body;
  body.model_path = models + "/dual_arm.xml";
  body.keyframe = "home";
  body.margin_spheres = {{"left_margin", "left_link7", {0, 0, 0.107}, 0.08},
                         {"right_margin", "right_link7", {0, 0, 0.107}, 0.08}};
  body.distance_pairs = {{"hands", "geom:left_margin", "geom:right_margin"}};
  TwinModelConfig wiping;
  wiping.model_path = models + "/scene_wiping.xml";
  wiping.keyframe = "ready";
  wiping.contact_pairs = {{"wiper_panel", "body:wiper", "geom:panel"}};
  wiping.distance_pairs = {{"wiper_panel", "geom:wiper_head", "geom:panel"}};
  return {{"single arm (panda.xml)", arm}, {"two-arm body (dual_arm.xml)", body}, {"wiping scene", wiping}};
}

struct Stats {
  std::vector<int64_t> ns;
  double percentile_us(double p) {
    std::sort(ns.begin(), ns.end());
    return static_cast<double>(ns[static_cast<size_t>(p * static_cast<double>(ns.size() - 1))]) * 1e-3;
  }
  double mean_us() const {
    double sum = 0;
    for (int64_t v : ns) sum += static_cast<double>(v);
    return sum / static_cast<double>(ns.size()) * 1e-3;
  }
};

// one twin cycle without the network: coupling step plus the observations
void twin_step(TwinSimulation& twin, const JointVector& home, int64_t k) {
  JointVector target = home;
  for (size_t i = 0; i < twin.joints(); ++i) target[i] += 0.1 * std::sin(2 * M_PI * 0.5 * static_cast<double>(k) * 1e-3);
  twin.step_coupled(target);
  for (size_t p = 0; p < twin.contact_pairs().size(); ++p) (void)twin.contact_wrench(p);
  for (size_t p = 0; p < twin.distance_pairs().size(); ++p) (void)twin.distance_m(p);
}

void run_case(Case& c, int rounds, int steps_per_round) {
  TwinSimulation twin(c.config);
  const JointVector home = twin.q_rad();
  // bare: the same compiled model (margins included), the arm resting without gravity as the
  // compensated twin does, nothing applied
  teleop::sim::MujocoModel bare = teleop::sim::load_with_additions(c.config.model_path, teleop::twin::margin_geometry(c.config));
  bare.model()->opt.gravity[2] = 0;
  bare.reset(c.config.keyframe);
  Stats bare_stats;
  Stats twin_stats;
  int64_t k = 0;
  for (int r = 0; r < rounds; ++r) {
    for (int s = 0; s < steps_per_round; ++s) {
      const int64_t t0 = teleop::monotonic_now_ns();
      mj_step(bare.model(), bare.data());
      bare_stats.ns.push_back(teleop::monotonic_now_ns() - t0);
    }
    for (int s = 0; s < steps_per_round; ++s, ++k) {
      const int64_t t0 = teleop::monotonic_now_ns();
      twin_step(twin, home, k);
      twin_stats.ns.push_back(teleop::monotonic_now_ns() - t0);
    }
  }
  const double dt_us = twin.simulation().model()->opt.timestep * 1e6;
  const double bare_mean = bare_stats.mean_us();
  const double twin_mean = twin_stats.mean_us();
  std::printf("| %-28s | %2d | %7.1f | %7.1f | %7.1f | %7.1f | %7.1f | %7.1f | %6.0f | %6.0f | %5.2f |\n", c.name,
              twin.simulation().model()->nv, bare_stats.percentile_us(0.5), bare_mean, bare_stats.percentile_us(0.99),
              twin_stats.percentile_us(0.5), twin_mean, twin_stats.percentile_us(0.99), dt_us / bare_mean,
              dt_us / twin_mean, twin_mean / bare_mean);
  if (twin.warnings() > 0 || bare.data()->warning[mjWARN_BADQACC].number > 0) std::printf("  (MuJoCo warnings in this case)\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop twin bench: twin step cost and real-time factor beside bare mj_step", "teleop_twin_bench"};
  std::string models = TELEOP_MODELS_DIR;
  int rounds = 20;
  int steps = 500;
  app.add_option("--models", models, "folder of the MJCF models");
  app.add_option("--rounds", rounds, "alternating rounds per case");
  app.add_option("--steps", steps, "steps per round and side");
  CLI11_PARSE(app, argc, argv);
  std::printf("%d rounds x %d steps per side and case; times in us per step (1 ms model timestep)\n\n", rounds, steps);
  std::printf("| model                        | nv | bare p50 | bare mean | bare p99 | twin p50 | twin mean | twin p99 | RT bare | RT twin | twin/bare |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (Case& c : cases(models)) run_case(c, rounds, steps);
  return 0;
}
