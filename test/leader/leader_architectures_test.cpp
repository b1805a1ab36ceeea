// The leader's part of each architecture (leader/src/architectures/): one for every architecture
// of the registry, built by name, with the channel and the authority writer the architecture
// says. Their laws, cycle by cycle, are pinned by leader_lockstep_trace_test.
#include "architectures/leader_architectures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "node_harness.h"
#include "teleop/transport/arm_topic.h"

namespace teleop::leader {
namespace {

LeaderConfig config() {
  auto root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader.yaml");
  return parse_leader_config(root);
}

TEST(LeaderArchitectures, HasAPartForEveryArchitectureOfTheRegistry) {
  std::vector<std::string_view> registry;
  for (const runtime::Architecture& a : runtime::architectures()) registry.push_back(a.name);
  EXPECT_EQ(leader_architecture_names(), registry);
}

// what a leader node hands its architecture
class LeaderArchitecturesTest : public ::testing::Test {
 protected:
  const LeaderConfig c = config();
  test::NodeHarness harness{"leader"};
  transport::Subscription<msg::JointState> follower_state{harness.node_participant, transport::topics::kFollowerState};
  transport::Subscription<msg::WrenchStamped> follower_wrench{harness.node_participant,
                                                              transport::topics::kFollowerWrench};
  transport::Subscription<msg::JointTorque> twin_feedback{harness.node_participant, transport::topics::kTwinFeedback};
  transport::Publication<msg::JointState> device_state{harness.node_participant, transport::topics::kLeaderState,
                                                       "leader"};
  const LeaderSetup setup{c, harness.context, 1e-3, {follower_state, follower_wrench, twin_feedback}, device_state};
};

TEST_F(LeaderArchitecturesTest, EachPartCommandsOnItsArchitecturesChannel) {
  const std::vector<std::pair<std::string, std::string>> expected{
      {"position_position", transport::topics::kLeaderCommand.name},
      {"pfc", transport::topics::kLeaderCartesian.name},
      {"pfc_tdpa", transport::topics::kLeaderCartesian.name},
      {"mmt", transport::topics::kLeaderState.name},  // the twin takes the device's state
  };
  for (const auto& [name, topic] : expected) {
    const auto part = make_leader_architecture(*runtime::find_architecture(name), setup);
    EXPECT_EQ(part->authority_topic(), topic) << name;
    EXPECT_EQ(part->cartesian(), runtime::is_cartesian(*runtime::find_architecture(name))) << name;
    // only the architectures with a TDPA channel have an energy to show
    EXPECT_EQ(std::isnan(part->observed_energy_j()), !part->cartesian()) << name;
  }
  EXPECT_EQ(make_leader_architecture(*runtime::find_architecture("mmt"), setup)->authority_writer(),
            device_state.writer_id());
}

TEST_F(LeaderArchitecturesTest, AnArchitectureWithoutALeaderPartIsAProgrammingError) {
  const runtime::Architecture wave{"wave_variables", runtime::CommandPath::kLeaderCartesian, false};
  EXPECT_THROW((void)make_leader_architecture(wave, setup), std::logic_error);
}

}  // namespace
}  // namespace teleop::leader
