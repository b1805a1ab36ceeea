// The `canopen:` keys of a follower's section: one mapping per drive in the joints' order, the
// bus's timing with its defaults, and a clear error naming the key for what cannot work.
#include <gtest/gtest.h>

#include <string>

#include "canopen_arm_bus.h"
#include "canopen_hardware.h"
#include "follower_section.h"
#include "teleop/common/config.h"
#include "teleop/robot/canopen_backend.h"

namespace teleop::robot {
namespace {

const std::string kDrive = "{bus: can0, node: 1, gear_ratio: 100, encoder_ticks_per_rev: 4096, rated_torque_mnm: 500, "
                           "max_torque_nm: 80}";

CanopenHardwareConfig parse(const std::string& yaml) {
  return test::parse_follower_section(yaml, parse_canopen_hardware);
}
std::string error_of(const std::string& yaml) { return test::follower_section_error(yaml, parse_canopen_hardware); }

TEST(CanopenHardwareConfig, ReadsEachDriveAndDefaultsTheTiming) {
  const CanopenHardwareConfig c = parse(
      "follower:\n  canopen:\n    drives:\n      - " + kDrive +
      "\n      - {bus: can1, node: 2, gear_ratio: 50, gear_efficiency: 0.9, encoder_ticks_per_rev: 65536, "
      "rated_torque_mnm: 250, offset_rad: -0.5, inverted: true, max_torque_nm: 40, q_min_rad: -2, q_max_rad: 2}\n");
  ASSERT_EQ(c.joints.size(), 2u);
  EXPECT_EQ(c.joints[0].bus, "can0");
  EXPECT_EQ(c.joints[0].node, 1);
  EXPECT_DOUBLE_EQ(c.joints[0].axis.rated_torque_nm, 0.5);
  EXPECT_DOUBLE_EQ(c.joints[0].axis.gear_efficiency, 1.0);
  EXPECT_EQ(c.joints[1].bus, "can1");
  EXPECT_TRUE(c.joints[1].axis.inverted);
  EXPECT_DOUBLE_EQ(c.joints[1].axis.offset_rad, -0.5);
  EXPECT_DOUBLE_EQ(c.joints[1].q_max_rad, 2.0);
  EXPECT_EQ(c.master_node, 127);
  EXPECT_EQ(c.master_lost_after_ms, 50);
  EXPECT_EQ(c.sync_divider, 1u);
  EXPECT_DOUBLE_EQ(c.state_timeout_s, 0.005);
}

TEST(CanopenHardwareConfig, NamesTheKeyOfWhatCannotWork) {
  EXPECT_NE(error_of("follower:\n  canopen:\n    drives: []\n").find("drives"), std::string::npos);
  EXPECT_NE(error_of("follower:\n  canopen:\n    drives:\n      - {bus: can0, node: 1}\n").find("gear_ratio"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  canopen:\n    drives:\n      - " + kDrive + "\n      - " + kDrive + "\n")
                .find("gives node 1 on can0 to joints 1 and 2"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  canopen:\n    drives:\n      - " + kDrive +
                     "\n    master_heartbeat_ms: 50\n    master_lost_after_ms: 50\n")
                .find("master_lost_after_ms"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  canopen:\n    drives:\n      - {bus: can0, node: 128, gear_ratio: 1, "
                     "encoder_ticks_per_rev: 1, rated_torque_mnm: 1, max_torque_nm: 1}\n")
                .find("node"),
            std::string::npos);
}

// The shipped example (config/nodes/follower_canopen_arm.yaml): seven drives on four buses, each
// bus within the load the master accepts at 1 kHz (the VM HIL runs it; docs/can_bus_budget.md).
TEST(CanopenHardwareConfig, TheShippedExampleIsSevenDrivesOnFourBusesEachWithinTheLoadLimit) {
  const CanopenHardwareConfig c =
      parse_canopen_hardware(ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower_canopen_arm.yaml")
                                 .child("follower"))
          ->config();
  ASSERT_EQ(c.joints.size(), 7u);
  const std::vector<std::string> buses = CanopenHardware::interfaces(c);
  EXPECT_EQ(buses, (std::vector<std::string>{"can0", "can1", "can2", "can3"}));
  for (const std::string& bus : buses) {
    const can::BusLoad load = canopen_bus_load(canopen_bus_config(c, bus, 1e-3 * c.sync_divider));
    EXPECT_FALSE(load.exceeds()) << bus << ": " << 100.0 * load.load_worst_case << " %";
  }
}

}  // namespace
}  // namespace teleop::robot
