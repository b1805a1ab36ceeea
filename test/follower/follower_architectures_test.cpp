// The follower's part of each architecture (follower/src/architectures/): one for every
// architecture of the registry, built by name, waiting for the stream the architecture commands
// on. Their laws, cycle by cycle, are pinned by follower_lockstep_trace_test.
#include "architectures/follower_architectures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "node_harness.h"

namespace teleop::follower {
namespace {

TEST(FollowerArchitectures, HasAPartForEveryArchitectureOfTheRegistry) {
  std::vector<std::string_view> registry;
  for (const runtime::Architecture& a : runtime::architectures()) registry.push_back(a.name);
  EXPECT_EQ(follower_architecture_names(), registry);
}

class FollowerArchitecturesTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"follower"};
  std::string arm;

  std::unique_ptr<FollowerArchitecture> make(const runtime::TeleoperationConfig* teleoperation) {
    return make_follower_architecture({harness.node_participant, harness.node_config.name, arm, 1e-3, teleoperation});
  }
};

TEST_F(FollowerArchitecturesTest, EachPartWaitsForItsArchitecturesStream) {
  for (const runtime::Architecture& a : runtime::architectures()) {
    runtime::TeleoperationConfig t;
    t.architecture = &a;
    const auto part = make(&t);
    EXPECT_EQ(part->cartesian(), runtime::is_cartesian(a)) << a.name;
    // only the Cartesian architectures have a TDPA channel, and so an energy to show
    EXPECT_EQ(std::isnan(part->observed_energy_j()), !part->cartesian()) << a.name;
  }
  // without a teleoperation section: the joint commands, as they come
  const auto plain = make(nullptr);
  EXPECT_FALSE(plain->cartesian());
  EXPECT_EQ(plain->correct(ValidCommand{}, true, control::Vector6::Zero()), nullptr);
}

TEST_F(FollowerArchitecturesTest, AnArchitectureWithoutAFollowerPartIsAProgrammingError) {
  const runtime::Architecture wave{"wave_variables", runtime::CommandPath::kLeaderCartesian, false};
  runtime::TeleoperationConfig t;
  t.architecture = &wave;
  EXPECT_THROW((void)make(&t), std::logic_error);
}

}  // namespace
}  // namespace teleop::follower
