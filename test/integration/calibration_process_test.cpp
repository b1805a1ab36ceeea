// teleop_calibrate as a lab runs it (docs/calibration.md): on the simulated arm carrying a tool it
// was not told about, it drives the poses at the node's rate and writes the robot's calibration,
// which the follower then applies at start; a run stopped midway writes nothing; a config with
// nowhere to write is refused before the robot moves.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>

#include "process_helpers.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

const std::string kTool = "follower.mujoco.payload={mass_kg: 1.2, com_m: [0.02, -0.01, 0.06]}";

std::vector<std::string> calibrate(const std::string& config, const std::vector<std::string>& extra) {
  std::vector<std::string> argv = {bin("teleop_calibrate"), "--config", config, "--set", kTool};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return argv;
}

TEST(CalibrateProcess, WritesTheToolsCalibrationWhichTheFollowerApplies) {
  const std::string dir = make_temp_dir();
  const std::string config = config_copy(dir, "follower.yaml", {});
  const std::string out = dir + "/panda.yaml";
  const ProcessResult run = run_process(
      calibrate(config, {"--out", out, "--set",
                         "follower.calibration.poses=[{q_rad: [0, -0.785, 0, -2.356, 0, 1.571, 0.785]}, "
                         "{q_rad: [0, -0.785, 0, -2.356, 1.2, 1.571, 0.785]}, {q_rad: [0, -0.3, 0, -2.0, 0, 2.5, 0.785]}, "
                         "{q_rad: [0.5, -0.5, 0, -1.8, 1.5, 1.2, 0]}]",
                         "--set", "follower.calibration.move_s=0.8", "--set", "follower.calibration.approach_s=0.3",
                         "--set", "follower.calibration.settle_s=0.5", "--set", "follower.calibration.measure_s=0.2"}),
      120s);
  ASSERT_TRUE(run.exit_status.has_value()) << run.output;
  ASSERT_EQ(*run.exit_status, 0) << run.output;
  EXPECT_NE(run.output.find("pose 4 of 4 measured"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("wrote " + out), std::string::npos) << run.output;
  const std::string written = read_file(out);
  EXPECT_NE(written.find("mass_kg: 1.1"), std::string::npos) << written;  // 1.2 kg within a few per cent

  const ProcessResult node = run_process({bin("teleop_follower"), "--config", config, "--domain",
                                          std::to_string(unique_domain()), "--duration", "1", "--set", kTool, "--set",
                                          "follower.calibration.file=" + out},
                                         60s);
  ASSERT_TRUE(node.exit_status.has_value()) << node.output;
  EXPECT_EQ(*node.exit_status, 0) << node.output;
  EXPECT_NE(node.output.find("calibration " + out + ": payload 1.1"), std::string::npos) << node.output;
}

TEST(CalibrateProcess, AStoppedRunWritesNothing) {
  const std::string dir = make_temp_dir();
  const std::string out = dir + "/panda.yaml";
  RunningProcess run(calibrate(config_copy(dir, "follower.yaml", {}), {"--out", out}));
  ASSERT_TRUE(run.wait_for_output("pose 1 of 8 measured", 60s)) << run.output();
  const auto status = run.stop(SIGINT, 10s);
  ASSERT_TRUE(status.has_value()) << run.output();
  EXPECT_EQ(*status, 1) << run.output();
  EXPECT_NE(run.output().find("stopped after 1 of 8 poses; nothing written"), std::string::npos) << run.output();
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CalibrateProcess, NowhereToWriteIsRefusedBeforeTheRobotMoves) {
  const ProcessResult run = run_process({bin("teleop_calibrate"), "--config", "follower"}, 30s);
  ASSERT_TRUE(run.exit_status.has_value()) << run.output;
  EXPECT_EQ(*run.exit_status, 2) << run.output;
  EXPECT_NE(run.output.find("no follower.calibration.file and no --out"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("poses,"), std::string::npos) << "nothing started";
}

}  // namespace
}  // namespace teleop::test
