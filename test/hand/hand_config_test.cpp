// The hand node's configuration: the shipped file, and errors that name file, key and problem.
#include "teleop/hand/hand_config.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::hand {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    const ConfigNode root = ConfigNode::load_string(yaml, "hand.yaml");
    parse_hand_config(root);
    root.check_all_used();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal = "node: {rate_hz: 250}\nhand:\n  interface: vcan0\n";

TEST(HandConfig, ReadsTheShippedFile) {
  const ConfigNode root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/hand.yaml");
  const HandNodeConfig c = parse_hand_config(root);
  EXPECT_EQ(c.interface, "vcan0");
  EXPECT_EQ(c.adapter.cycle_rate_hz, 250.0);
  EXPECT_EQ(c.adapter.node_ids[8], 9);
  EXPECT_EQ(c.adapter.channels[0].gear_ratio, 100.0);
  EXPECT_DOUBLE_EQ(c.adapter.heartbeat_timeout_s, 0.35);
  EXPECT_FALSE(c.adapter.homing.enabled);
}

TEST(HandConfig, DefaultsFillWhatIsMissing) {
  EXPECT_EQ(error_of(kMinimal), "");
}

TEST(HandConfig, ErrorsNameTheKey) {
  EXPECT_NE(error_of(std::string(kMinimal) + "  node_ids: [1, 2, 3]\n").find("hand.node_ids"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "  sign: [1, 1, 1, 1, 1, 1, 1, 1, 0.5]\n").find("hand.sign: each entry"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "  node_ids: [1, 2, 3, 4, 5, 6, 7, 8, 8]\n").find("node id 8 used twice"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "  gains: {position_kp: 3}\n").find("hand.gains.position_kp"),
            std::string::npos);
  EXPECT_NE(error_of("node: {rate_hz: 250}\nhand: {}\n").find("hand.interface"), std::string::npos);
}

}  // namespace
}  // namespace teleop::hand
