// teleop_box_plan: turns the box task's plan (config/tasks/box_task.yaml) into the two joint
// trajectories the simulated operator pulls the haptic devices along (docs/box_task.md).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "hand_trajectories.h"
#include "teleop/common/version.h"

int main(int argc, char** argv) {
  CLI::App app{"teleop_box_plan: joint trajectories of both hands for the two-arm box task"};
  app.set_version_flag("--version", teleop::version_text());
  std::string plan_path;
  std::string left_csv;
  std::string right_csv;
  double tolerance_m = 1e-3;
  app.add_option("--plan", plan_path, "plan YAML (config/tasks/box_task.yaml)")->required();
  app.add_option("--left", left_csv, "left hand's trajectory CSV to write")->required();
  app.add_option("--right", right_csv, "right hand's trajectory CSV to write")->required();
  app.add_option("--tolerance", tolerance_m, "largest flange position error the IK may leave [m]");
  CLI11_PARSE(app, argc, argv);

  try {
    const auto plan = teleop::box_task::load_box_plan(plan_path);
    const auto trajectories = teleop::box_task::plan_hand_trajectories(plan);
    bool reached = true;
    for (const auto& hand : trajectories) {
      std::printf("%s: %zu rows, worst IK error %.2e m %.2e rad, closest to a joint limit %.3f rad\n",
                  teleop::box_task::side_name(hand.side), hand.t_s.size(), hand.worst.position_m, hand.worst.rotation_rad,
                  hand.min_limit_distance_rad);
      reached = reached && hand.worst.position_m <= tolerance_m;
    }
    if (!reached) {
      std::fprintf(stderr, "%s: a hand cannot reach the plan within %g m (nothing written)\n", plan_path.c_str(),
                   tolerance_m);
      return 1;
    }
    teleop::box_task::write_trajectory_csv(trajectories[0], left_csv);
    teleop::box_task::write_trajectory_csv(trajectories[1], right_csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
