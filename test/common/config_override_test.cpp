// ConfigNode::apply_override: the `--set KEY=VALUE` of every node.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "alias_bomb.h"
#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop {
namespace {

constexpr Range kAny{-1e9, 1e9};

ConfigNode load(const std::string& text) { return ConfigNode::load_string(text, "node.yaml"); }
std::string error_of(const std::function<void()>& f) { return test::error_of<ConfigError>(f); }

TEST(ConfigOverride, ReplacesAScalarInANestedMapping) {
  ConfigNode c = load("teleoperation:\n  architecture: pfc\n  gain: 2\n");
  c.apply_override("teleoperation.architecture=pfc_tdpa");
  const ConfigNode t = c.child("teleoperation");
  EXPECT_EQ(t.get_string("architecture"), "pfc_tdpa");
  EXPECT_DOUBLE_EQ(t.get_double("gain", kAny), 2.0);
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigOverride, ParsesTheValueAsYamlWhenItIsAList) {
  ConfigNode c = load("leader:\n  amplitudes_rad: [0, 0, 0]\n");
  c.apply_override("leader.amplitudes_rad=[0,0.2,0,0.2,0,0,0]");
  const auto a = c.child("leader").get_double_list("amplitudes_rad", kAny);
  ASSERT_EQ(a.size(), 7u);
  EXPECT_DOUBLE_EQ(a[1], 0.2);
  EXPECT_DOUBLE_EQ(a[3], 0.2);
}

TEST(ConfigOverride, CreatesMissingMappingsOnThePath) {
  ConfigNode c = load("node:\n  name: x\n");
  c.apply_override("a.b.c=5");
  EXPECT_EQ(c.child("a").child("b").get_int("c", kAny), 5);
  EXPECT_EQ(c.child("node").get_string("name"), "x");
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigOverride, LaterOverridesWinWhenTheSameKeyIsSetTwice) {
  ConfigNode c = load("x: 1\n");
  c.apply_override("x=2");
  c.apply_override("x=3");
  EXPECT_EQ(c.get_int("x", kAny), 3);
}

TEST(ConfigOverride, ReportsAMalformedSpecNamingTheArgument) {
  ConfigNode c = load("x: 1\n");
  EXPECT_EQ(error_of([&] { c.apply_override("x"); }), "node.yaml: --set x: expected KEY=VALUE, e.g. node.duration_s=5");
  EXPECT_NE(error_of([&] { c.apply_override("=1"); }).find("--set =1: expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(error_of([&] { c.apply_override("x="); }).find("--set x=: expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(error_of([&] { c.apply_override("a..b=1"); }).find("--set a..b=1: empty key segment"), std::string::npos);
  EXPECT_NE(error_of([&] { c.apply_override("x=[1,"); }).find("--set x=[1,: malformed YAML value"), std::string::npos);
}

TEST(ConfigOverride, RefusesAnAliasBombAsAValueNamingTheArgument) {
  ConfigNode c = load("x: 1\n");
  const std::string spec = "x=" + test::alias_bomb(11);
  EXPECT_EQ(error_of([&] { c.apply_override(spec); }), "node.yaml (--set " + spec + "):6: x." + test::kAliasBombError);
}

TEST(ConfigOverride, RefusesAPathThroughAScalar) {
  ConfigNode c = load("x: 1\n");
  EXPECT_EQ(error_of([&] { c.apply_override("x.y=2"); }), "node.yaml: --set x.y=2: x is '1', not a mapping");
}

TEST(ConfigOverride, NamesTheArgumentWhenTheKeyIsUnknown) {
  ConfigNode c = load("node:\n  name: x\n");
  c.apply_override("node.bogus=1");
  c.child("node").get_string("name");
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "node.yaml (--set node.bogus=1): node.bogus: unknown key");
}

TEST(ConfigOverride, NamesTheArgumentWhenItCreatedAnUnknownSection) {
  ConfigNode c = load("node:\n  name: x\n");
  c.apply_override("nosuch.key=1");
  c.child("node").get_string("name");
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "node.yaml (--set nosuch.key=1): nosuch: unknown key");
}

TEST(ConfigOverride, NamesTheArgumentWhenTheValueIsBad) {
  ConfigNode c = load("node:\n  rate_hz: 1000\n");
  c.apply_override("node.rate_hz=-5");
  EXPECT_EQ(error_of([&] {
              c.child("node").get_double("rate_hz", Range{1, 10'000});
            }),
            "node.yaml (--set node.rate_hz=-5): node.rate_hz: value -5 is out of range [1, 10000]");
}

TEST(ConfigOverride, KeepsFileLinesForKeysFromTheFile) {
  ConfigNode c = load("node:\n  name: x\n  bogus: 2\n");
  c.apply_override("node.name=y");
  c.child("node").get_string("name");
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "node.yaml:3: node.bogus: unknown key");
}

TEST(ConfigNode, ReturnsAValueAsFlowYamlForPassingItOn) {
  const ConfigNode c = load("s: pfc_tdpa\nl: [0, 0.2]\nm: {a: 1}\n");
  EXPECT_EQ(c.get_yaml("s"), "pfc_tdpa");
  EXPECT_EQ(c.get_yaml("l"), "[0, 0.2]");
  EXPECT_EQ(c.get_yaml("m"), "{a: 1}");
  EXPECT_NO_THROW(c.check_all_used());
}

}  // namespace
}  // namespace teleop
