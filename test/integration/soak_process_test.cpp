// The soak's short form (issue 16; the long form is scripts/soak.sh, its table in
// docs/reliability.md): leader, twin and follower of the model-mediated stiff wall, over a network
// with outages and 50 % bursty loss, each killed with SIGKILL once at a random moment and started
// again. Every kill must bring the nodes that depend on the dead one into their safe state, and no
// cycle of the robot may apply a stale command, exceed a torque limit or cross a reflex threshold
// unlatched. (How fast they resume under that loss is measured, not bounded: DDS discovery over a
// lossy link takes seconds.)
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "process_helpers.h"

namespace teleop::test {
namespace {

TEST(Soak, EveryKillReachesTheSafeStateAndTheRobotNeverAppliesAStaleCommand) {
  const std::string dir = make_temp_dir();
  const ProcessResult run = run_process({bin("teleop"), "soak", source("config/experiments/soak.yaml"), "--kills-per-node",
                                         "1", "--domain", std::to_string(unique_domain()), "--report-dir", dir},
                                        std::chrono::seconds(240));
  ASSERT_TRUE(run.exit_status.has_value()) << run.output;
  EXPECT_EQ(*run.exit_status, 0) << run.output;
  EXPECT_NE(run.output.find("stale commands applied 0, torque-limit violations 0, reflex-threshold violations 0"),
            std::string::npos)
      << run.output;

  std::istringstream csv(read_file(dir + "/soak_mmt_stiff_wall.csv"));
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line, "node,incarnation,killed_s,restarted_s,first_cycle_s,to_safe_ms,to_resume_ms,interrupted,pending");
  int events = 0;
  while (std::getline(csv, line)) {
    ++events;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9u) << line;
    const double to_safe_ms = std::stod(cells[5]);
    EXPECT_TRUE(std::isfinite(to_safe_ms)) << "every kill is noticed: " << line;
    EXPECT_TRUE(std::isfinite(std::stod(cells[4]))) << "the restarted process ran: " << line;
    ::testing::Test::RecordProperty(cells[0] + "_to_safe_ms", cells[5]);
  }
  EXPECT_EQ(events, 3) << "one kill of each of leader, twin and follower";
}

}  // namespace
}  // namespace teleop::test
