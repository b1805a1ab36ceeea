// What the doctor reads out of node configs and scenarios, with the nodes' own parsers
// (doctor/host_needs.h).
#include <gtest/gtest.h>

#include "process_helpers.h"
#include "teleop/common/config.h"
#include "teleop/doctor/host_needs.h"

namespace teleop::doctor {
namespace {

TEST(DoctorNeeds, TheHandNeedsItsBusAtItsBitrate) {
  const HostNeeds needs = needs_of({test::source("config/nodes/hand.yaml")});
  ASSERT_EQ(needs.can.size(), 1u);
  EXPECT_EQ(needs.can[0].interface, "vcan0");
  EXPECT_EQ(needs.can[0].bitrate_bps, 1e6);
  EXPECT_EQ(needs.can[0].node, "hand");
  ASSERT_EQ(needs.realtime.size(), 1u);
  EXPECT_FALSE(needs.realtime_required());
}

TEST(DoctorNeeds, AnArmOfDrivesNeedsEachOfItsBusesOnce) {
  const HostNeeds needs = needs_of({test::source("config/nodes/follower_canopen_arm.yaml")});
  std::vector<std::string> buses;
  for (const CanNeed& c : needs.can) buses.push_back(c.interface);
  EXPECT_EQ(buses, (std::vector<std::string>{"can0", "can1", "can2", "can3"}));
  ASSERT_EQ(needs.dds.size(), 1u);
  EXPECT_TRUE(needs.dds[0].multicast_discovery);
}

TEST(DoctorNeeds, ALeadersMasterArmOfDrivesNeedsItsBusesToo) {
  const HostNeeds needs = needs_of({test::source("config/nodes/leader_canopen_arm.yaml")});
  std::vector<std::string> buses;
  for (const CanNeed& c : needs.can) buses.push_back(c.interface + " " + c.node);
  EXPECT_EQ(buses, (std::vector<std::string>{"can0 leader", "can1 leader", "can2 leader", "can3 leader"}));
  EXPECT_TRUE(needs_of({test::source("config/nodes/leader_haptic_arm.yaml")}).can.empty()) << "a simulated device";
}

TEST(DoctorNeeds, AScenarioAddsItsNodesWithTheirOverrides) {
  const std::string dir = test::make_temp_dir();
  const std::string follower = test::config_copy(dir, "follower.yaml", {});
  test::write_file(dir + "/rt.yaml",
                   "scenario: {name: rt}\n"
                   "nodes:\n"
                   "  - {name: follower, executable: teleop_follower, config: follower.yaml,\n"
                   "     set: {node.realtime: required, node.realtime_priority: 91, transport.interface_whitelist: [10.1.2.3]}}\n");
  const HostNeeds needs = needs_of({dir + "/rt.yaml"});
  ASSERT_EQ(needs.realtime.size(), 1u);
  EXPECT_TRUE(needs.realtime_required());
  EXPECT_EQ(needs.highest_priority(), 91);
  EXPECT_EQ(needs.judged_priority(), 91);
  ASSERT_EQ(needs.dds.size(), 1u);
  EXPECT_EQ(needs.dds[0].interface_whitelist, (std::vector<std::string>{"10.1.2.3"}));
}

TEST(DoctorNeeds, WithoutConfigsTheDefaultPriorityIsJudged) {
  const HostNeeds none = needs_of({});
  EXPECT_EQ(none.highest_priority(), 0);
  EXPECT_EQ(none.judged_priority(), 80);
  EXPECT_FALSE(none.realtime_required());
}

TEST(DoctorNeeds, AMalformedConfigNamesFileAndKey) {
  const std::string dir = test::make_temp_dir();
  test::write_file(dir + "/bad.yaml", "node:\n  name: x\n  realtime: sometimes\n");
  try {
    needs_of({dir + "/bad.yaml"});
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("realtime"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::doctor
