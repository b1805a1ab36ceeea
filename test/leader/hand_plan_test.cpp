// The simulated operator's hand: keyframes, smoothstep between them, the plan file and its errors.
#include "hand_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "leader_config.h"

namespace teleop::leader {
namespace {

HandMotors all(double v) {
  HandMotors m{};
  m.fill(v);
  return m;
}

TEST(HandPlan, MovesAlongASmoothstepBetweenKeyframesAndHoldsTheLast) {
  const HandPlan plan({{0.0, all(0.0), all(0.0)}, {2.0, all(0.8), all(1.0)}, {3.0, all(0.4), all(0.5)}});
  HandMotors q{};
  HandMotors limit{};
  plan.sample(-1.0, q, limit);
  EXPECT_EQ(q, all(0.0));
  plan.sample(1.0, q, limit);  // halfway: smoothstep 0.5
  EXPECT_NEAR(q[4], 0.4, 1e-12);
  EXPECT_EQ(limit, all(1.0));  // the limit of the keyframe it moves to
  plan.sample(0.5, q, limit);
  EXPECT_NEAR(q[0], 0.8 * 0.25 * 0.25 * (3 - 2 * 0.25), 1e-12);
  plan.sample(2.0, q, limit);
  EXPECT_NEAR(q[8], 0.8, 1e-12);
  plan.sample(10.0, q, limit);
  EXPECT_EQ(q, all(0.4));
  EXPECT_EQ(limit, all(0.5));
}

TEST(HandPlan, RefusesKeyframesOutOfOrderOrNotFinite) {
  EXPECT_THROW(HandPlan({}), std::invalid_argument);
  EXPECT_THROW(HandPlan({{1.0, all(0), all(0)}, {1.0, all(0), all(0)}}), std::invalid_argument);
  EXPECT_THROW(HandPlan({{-1.0, all(0), all(0)}}), std::invalid_argument);
  EXPECT_THROW(HandPlan({{0.0, all(std::nan("")), all(0)}}), std::invalid_argument);
  EXPECT_THROW(HandPlan({{0.0, all(0), all(-1)}}), std::invalid_argument);
}

TEST(HandPlan, ReadsTheShippedOperatorGrasp) {
  const ConfigNode root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader_hand.yaml");
  const LeaderConfig c = parse_leader_config(root);
  ASSERT_TRUE(c.hand.has_value());
  EXPECT_EQ(c.hand->keyframes().size(), 5u);
  HandMotors q{};
  HandMotors limit{};
  c.hand->sample(5.0, q, limit);
  EXPECT_NEAR(q[1], 0.9, 1e-12);  // thumb opposed
  EXPECT_EQ(limit[2], 1.0);
  // leader.yaml commands no hand
  EXPECT_FALSE(parse_leader_config(ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader.yaml"))
                   .hand.has_value());
}

TEST(HandPlan, ConfigErrorsNameTheKey) {
  const auto parse = [](const std::string& plan) {
    return parse_hand_plan(ConfigNode::load_string("hand:\n  plan: " + plan + "\n", "leader.yaml").child("hand"));
  };
  EXPECT_NO_THROW(parse("[{t_s: 0, position_rad: [0, 0, 0, 0, 0, 0, 0, 0, 0]}]"));
  try {
    parse("[{t_s: 0, position_rad: [0, 0, 0]}]");
    FAIL() << "accepted 3 targets";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("position_rad"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("9 values"), std::string::npos) << e.what();
  }
  try {
    parse(
        "[{t_s: 1, position_rad: [0, 0, 0, 0, 0, 0, 0, 0, 0]}, {t_s: 0.5, position_rad: [0, 0, 0, 0, 0, 0, 0, 0, 0]}]");
    FAIL() << "accepted decreasing times";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("t_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse("[]"), ConfigError);
}

}  // namespace
}  // namespace teleop::leader
