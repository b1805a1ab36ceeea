// The launcher as a real process: bad scenarios, failing nodes, the demo by name from the source
// tree's root.
#include <gtest/gtest.h>

#include "process_helpers.h"

namespace teleop::test {
namespace {

TEST(LauncherProcess, RejectsABadScenarioNamingFileAndKey) {
  const std::string dir = make_temp_dir();
  write_file(dir + "/s.yaml", "scenario:\n  name: x\n  duration_s: -1\nnodes: []\n");
  const ProcessResult r = run_process({bin("teleop"), "launch", dir + "/s.yaml"}, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find(dir + "/s.yaml:3: scenario.duration_s: value -1 is out of range"), std::string::npos)
      << r.output;
}

TEST(LauncherProcess, FailsAndStopsTheOthersWhenANodeCannotStart) {
  const std::string dir = make_temp_dir();
  write_file(dir + "/bad.yaml", read_file(config_copy(dir, "leader.yaml", {})) + "bogus_section: 1\n");
  write_file(dir + "/s.yaml", "scenario:\n  name: failing\n  duration_s: 20\nnodes:\n"
                              "  - {name: follower, executable: teleop_follower, config: " +
                                  source("config/nodes/follower.yaml") +
                                  "}\n"
                                  "  - {name: leader, executable: teleop_leader, config: bad.yaml}\n");
  const ProcessResult r = run_process({bin("teleop"), "launch", dir + "/s.yaml", "--domain",
                                       std::to_string(unique_domain()), "--bin-dir", TELEOP_BIN_DIR},
                                      std::chrono::seconds(60));
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("bogus_section: unknown key"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("leader exited early with status 2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("RESULT: FAILED"), std::string::npos) << r.output;
}

// as the README's next steps run it, from the clone's root, where follower/, leader/ and twin/ are
// folders of code: the nodes' configs are found by name all the same
TEST(LauncherProcess, TheDemoRunsByNameFromTheSourceTreesRoot) {
  const ProcessResult r =
      run_process({"/bin/sh", "-c",
                   "cd '" + source("") + "' && exec '" + bin("teleop") + "' launch demo --duration 2 --domain " +
                       std::to_string(unique_domain()) + " --report-dir '" + make_temp_dir() + "'"},
                  std::chrono::seconds(60));
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_EQ(r.output.find("is a folder"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 nodes running"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace teleop::test
