#include "teleop/runtime/node_config.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::runtime {
namespace {

NodeConfig parse(const std::string& text, const std::string& default_name = "follower") {
  const ConfigNode root = ConfigNode::load_string(text, "node.yaml");
  NodeConfig c = parse_node_config(root.child("node"), default_name);
  root.check_all_used();
  return c;
}

std::string error_of(const std::string& text, const std::string& default_name = "follower") {
  try {
    parse(text, default_name);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return {};
}

TEST(ParseNodeConfig, AppliesDefaultsWhenSectionIsEmpty) {
  const NodeConfig c = parse("node: {}\n");
  EXPECT_EQ(c.name, "follower");
  EXPECT_DOUBLE_EQ(c.rate_hz, 1000.0);
  EXPECT_DOUBLE_EQ(c.status_rate_hz, 10.0);
  EXPECT_DOUBLE_EQ(c.duration_s, 0.0);
  EXPECT_EQ(c.max_catch_up_cycles, 10u);
  EXPECT_EQ(c.realtime.mode, RealtimeMode::kOff);
  EXPECT_EQ(c.realtime.priority, 80);
  EXPECT_EQ(c.period_ns(), 1'000'000);
}

TEST(ParseNodeConfig, MapsEachRealtimeChoiceToItsMode) {
  EXPECT_EQ(parse("node:\n  realtime: off\n").realtime.mode, RealtimeMode::kOff);
  EXPECT_EQ(parse("node:\n  realtime: optional\n").realtime.mode, RealtimeMode::kOptional);
  EXPECT_EQ(parse("node:\n  realtime: required\n  realtime_priority: 42\n").realtime.mode, RealtimeMode::kRequired);
  EXPECT_EQ(parse("node:\n  realtime_priority: 42\n").realtime.priority, 42);
}

TEST(ParseNodeConfig, RejectsUnknownRealtimeModeAndPriorityOutOfRange) {
  EXPECT_EQ(error_of("node:\n  realtime: always\n"),
            "node.yaml:2: node.realtime: 'always' is not one of: off, optional, required");
  EXPECT_EQ(error_of("node:\n  realtime_priority: 0\n"),
            "node.yaml:2: node.realtime_priority: value 0 is out of range [1, 99]");
  EXPECT_EQ(error_of("node:\n  realtime_priority: 100\n"),
            "node.yaml:2: node.realtime_priority: value 100 is out of range [1, 99]");
}

TEST(ParseNodeConfig, ReadsEveryKeyWhenGiven) {
  const NodeConfig c = parse(
      "node:\n"
      "  name: follower_left\n"
      "  rate_hz: 500\n"
      "  status_rate_hz: 2.5\n"
      "  duration_s: 12.5\n"
      "  max_catch_up_cycles: 3\n");
  EXPECT_EQ(c.name, "follower_left");
  EXPECT_DOUBLE_EQ(c.rate_hz, 500.0);
  EXPECT_DOUBLE_EQ(c.status_rate_hz, 2.5);
  EXPECT_DOUBLE_EQ(c.duration_s, 12.5);
  EXPECT_EQ(c.max_catch_up_cycles, 3u);
  EXPECT_EQ(c.period_ns(), 2'000'000);
}

TEST(ParseNodeConfig, AcceptsNameOfExactly31Characters) {
  const std::string name(31, 'n');
  EXPECT_EQ(parse("node:\n  name: " + name + "\n").name, name);
}

TEST(ParseNodeConfig, AcceptsStatusRateEqualToLoopRate) {
  const NodeConfig c = parse("node:\n  rate_hz: 50\n  status_rate_hz: 50\n");
  EXPECT_DOUBLE_EQ(c.status_rate_hz, c.rate_hz);
}

TEST(ParseNodeConfig, RejectsNameLongerThan31Characters) {
  EXPECT_EQ(error_of("node:\n  name: " + std::string(32, 'n') + "\n"),
            "node.yaml:2: node.name: must have 1 to 31 characters");
}

TEST(ParseNodeConfig, RejectsEmptyName) {
  EXPECT_EQ(error_of("node:\n  name: \"\"\n"), "node.yaml:2: node.name: must have 1 to 31 characters");
}

TEST(ParseNodeConfig, RejectsTooLongDefaultNameWhenNoNameGiven) {
  EXPECT_EQ(error_of("node:\n  rate_hz: 100\n", std::string(40, 'd')),
            "node.yaml:2: node.name: must have 1 to 31 characters");
}

TEST(ParseNodeConfig, RejectsStatusRateAboveLoopRate) {
  EXPECT_EQ(error_of("node:\n  rate_hz: 5\n  status_rate_hz: 10\n"),
            "node.yaml:3: node.status_rate_hz: must not exceed rate_hz");
}

TEST(ParseNodeConfig, RejectsRatesOutOfRange) {
  EXPECT_EQ(error_of("node:\n  rate_hz: 0\n"), "node.yaml:2: node.rate_hz: value 0 is out of range [1, 10000]");
  EXPECT_EQ(error_of("node:\n  rate_hz: 20000\n"), "node.yaml:2: node.rate_hz: value 20000 is out of range [1, 10000]");
  EXPECT_EQ(error_of("node:\n  rate_hz: .nan\n"), "node.yaml:2: node.rate_hz: value .nan is out of range [1, 10000]");
  EXPECT_EQ(error_of("node:\n  status_rate_hz: 0.01\n"),
            "node.yaml:2: node.status_rate_hz: value 0.01 is out of range [0.1, 100]");
  EXPECT_EQ(error_of("node:\n  status_rate_hz: 101\n"),
            "node.yaml:2: node.status_rate_hz: value 101 is out of range [0.1, 100]");
}

TEST(ParseNodeConfig, RejectsNegativeDurationAndCatchUp) {
  EXPECT_EQ(error_of("node:\n  duration_s: -1\n"), "node.yaml:2: node.duration_s: value -1 is out of range [0, 1e+06]");
  EXPECT_EQ(error_of("node:\n  max_catch_up_cycles: -1\n"),
            "node.yaml:2: node.max_catch_up_cycles: value -1 is out of range [0, 100000]");
  EXPECT_EQ(error_of("node:\n  max_catch_up_cycles: 2.5\n"),
            "node.yaml:2: node.max_catch_up_cycles: expected an integer, got '2.5'");
}

TEST(ParseNodeConfig, RejectsWrongTypes) {
  EXPECT_EQ(error_of("node:\n  rate_hz: fast\n"), "node.yaml:2: node.rate_hz: expected a number, got 'fast'");
  EXPECT_EQ(error_of("node:\n  name: [a, b]\n"), "node.yaml:2: node.name: expected a string, got a list");
  EXPECT_EQ(error_of("node: 5\n"), "node.yaml:1: node: expected a mapping, got '5'");
}

TEST(ParseNodeConfig, RejectsUnknownKey) {
  EXPECT_EQ(error_of("node:\n  rate_hz: 100\n  rate: 100\n"), "node.yaml:3: node.rate: unknown key");
}

}  // namespace
}  // namespace teleop::runtime
