// `teleop doctor` as a user runs it: on this host without configs (every check printed, exit 0
// unless something fails), with a config whose CAN bus is missing (exit 1 naming it and its fix),
// with a malformed config (exit 2 naming file and key).
#include <gtest/gtest.h>

#include <chrono>

#include "process_helpers.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

TEST(DoctorProcess, PrintsEveryCheckOfThisHost) {
  const ProcessResult r = run_process({bin("teleop"), "doctor"}, 30s);
  ASSERT_TRUE(r.exit_status.has_value()) << r.output;
  for (const char* check : {"kernel", "rtprio", "memlock", "rt throttling", "cpu governor", "clock", "input devices",
                            "dds", "provisioning"}) {
    EXPECT_NE(r.output.find("  " + std::string(check) + " "), std::string::npos) << check << "\n" << r.output;
  }
  // nothing configured needs anything that can fail; what this host lacks shows as warnings
  EXPECT_EQ(*r.exit_status, 0) << r.output;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
}

TEST(DoctorProcess, AMissingCanBusFailsNamingItsConfigAndFix) {
  const std::string dir = make_temp_dir();
  const std::string hand = config_copy(dir, "hand.yaml", {{"interface: vcan0", "interface: nocan7"}});
  const ProcessResult r = run_process({bin("teleop"), "doctor", hand}, 30s);
  ASSERT_TRUE(r.exit_status.has_value()) << r.output;
  EXPECT_EQ(*r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("FAIL  nocan7"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no such interface (hand, " + hand + ")"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sudo ip link add nocan7 type vcan"), std::string::npos) << r.output;
}

TEST(DoctorProcess, AMalformedConfigExits2NamingFileAndKey) {
  const std::string dir = make_temp_dir();
  write_file(dir + "/bad.yaml", "node:\n  name: x\n  realtime: sometimes\n");
  const ProcessResult r = run_process({bin("teleop"), "doctor", dir + "/bad.yaml"}, 30s);
  ASSERT_TRUE(r.exit_status.has_value()) << r.output;
  EXPECT_EQ(*r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.yaml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("realtime"), std::string::npos) << r.output;
}

TEST(DoctorProcess, ANamedScenarioIsCheckedNodeByNode) {
  const ProcessResult r = run_process({bin("teleop"), "doctor", "demo"}, 30s);
  ASSERT_TRUE(r.exit_status.has_value()) << r.output;
  EXPECT_NE(r.output.find("3 nodes checked"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace teleop::test
