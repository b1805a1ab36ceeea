#include "teleop/transport/impairment/link_profile.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "teleop/transport/impairment/impairment_config.h"

namespace teleop::transport::impairment {
namespace {

LinkProfile parse(const std::string& yaml) {
  const ConfigNode root = ConfigNode::load_string(yaml, "net.yaml");
  LinkProfile p = parse_link_profile(root.child("profile"));
  root.check_all_used();
  return p;
}

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LinkProfile, ReadsDelayJitterLossAndOutages) {
  const LinkProfile p = parse(
      "profile:\n"
      "  name: wan\n"
      "  delay_ms: 17.5\n"
      "  jitter_ms: 1\n"
      "  distribution: pareto\n"
      "  loss: {model: gilbert_elliott, p: 0.01, r: 0.3}\n"
      "  outages: [{start_s: 5, duration_s: 2}]\n");
  EXPECT_EQ(p.name, "wan");
  ASSERT_EQ(p.phases.size(), 1u);
  EXPECT_EQ(p.phases[0].delay_ns, 17'500'000);
  EXPECT_EQ(p.phases[0].jitter_ns, 1'000'000);
  EXPECT_EQ(p.phases[0].distribution, DelayDistribution::kPareto);
  EXPECT_EQ(p.phases[0].loss.model, LossModel::kGilbertElliott);
  EXPECT_DOUBLE_EQ(p.phases[0].loss.loss_in_bad, 1.0);
  ASSERT_EQ(p.outages.size(), 1u);
  EXPECT_EQ(p.outages[0].start_ns, 5'000'000'000);
  EXPECT_FALSE(p.is_transparent());
}

TEST(LinkProfile, ReadsATimeVaryingSchedule) {
  const LinkProfile p = parse(
      "profile:\n"
      "  name: schedule\n"
      "  duration_s: 5\n"
      "  phases:\n"
      "    - {duration_s: 10, delay_ms: 17.5}\n"
      "    - {duration_s: 2, loss: {model: bernoulli, probability: 0.2}}\n"
      "    - {}\n");
  ASSERT_EQ(p.phases.size(), 4u);
  EXPECT_EQ(p.phases[0].duration_ns, 5'000'000'000);
  EXPECT_EQ(p.phases[1].delay_ns, 17'500'000);
  EXPECT_EQ(p.phases[2].delay_ns, 0) << "a phase changes the top level, not the phase before";
  EXPECT_EQ(p.phases[2].loss.model, LossModel::kBernoulli);
  EXPECT_EQ(p.phases[3].loss.model, LossModel::kNone);
}

TEST(LinkProfile, RejectsBadValuesNamingTheKey) {
  EXPECT_EQ(error_of("profile:\n  name: x\n  loss: {model: bernoulli, probability: 1.5}\n"),
            "net.yaml:3: profile.loss.probability: value 1.5 is out of range [0, 1]");
  EXPECT_EQ(error_of("profile:\n  name: x\n  distribution: cauchy\n"),
            "net.yaml:3: profile.distribution: 'cauchy' is not one of: constant, uniform, normal, pareto");
  EXPECT_EQ(error_of("profile:\n  name: x\n  delay: 5\n"), "net.yaml:3: profile.delay: unknown key");
  EXPECT_EQ(error_of("profile:\n  name: x\n  loss: {model: gilbert_elliott, p: 0.1, r: 0}\n"),
            "net.yaml:3: profile.loss.r: must be > 0: the link would never leave the bad state");
}

TEST(LinkProfile, GilbertElliottExpectedLossCombinesBothStates) {
  LossSpec ge{LossModel::kGilbertElliott, 0, 0.1, 0.3, 0.8, 0.01};
  EXPECT_NEAR(ge.expected_loss_rate(), 0.25 * 0.8 + 0.75 * 0.01, 1e-12);
  EXPECT_NEAR(ge.expected_bad_run_length(), 1 / 0.3, 1e-12);
}

// a node config in a folder of its own (no network/ beside it) still names the shipped profiles;
// a profile beside it comes first
TEST(ProfilePath, FallsBackToTeleopsOwnProfilesByName) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("teleop_profile_path_" + std::to_string(getpid()));
  fs::create_directories(dir / "network");
  const std::string node_config = (dir / "node.yaml").string();
  EXPECT_EQ(resolve_profile_path("wan-35ms", node_config),
            std::string(TELEOP_SOURCE_DIR) + "/config/network/wan-35ms.yaml");
  EXPECT_EQ(resolve_profile_path("no-such-profile", node_config), "");
  std::ofstream((dir / "network" / "wan-35ms.yaml").string()) << "profile: {name: mine}\n";
  EXPECT_EQ(resolve_profile_path("wan-35ms", node_config), (dir / "network" / "wan-35ms.yaml").string());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace teleop::transport::impairment
