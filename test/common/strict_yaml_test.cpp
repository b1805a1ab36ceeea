#include "teleop/common/strict_yaml.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "alias_bomb.h"
#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop {
namespace {

std::string error_of(const std::function<void()>& f) { return test::error_of<ConfigError>(f); }

YAML::Node parse(const std::string& text) { return parse_strict_yaml(text, "test.yaml"); }

// `aliases` aliases of one anchored list of `items` scalars: each alias adds `items` nodes
std::string repeated_list(int items, int aliases) {
  std::string text = "block: &block [";
  for (int i = 0; i < items; ++i) text += (i == 0 ? "" : ", ") + std::to_string(i);
  text += "]\nuses:\n";
  for (int i = 0; i < aliases; ++i) text += "  - *block\n";
  return text;
}

TEST(StrictYaml, RefusesAThirtyLevelAliasBombAtTheAliasThatCrossesTheBudget) {
  // walked as a tree this is 9^31 nodes; the pass costs the 32 lines it reads
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = error_of([] { parse(test::alias_bomb(30)); });
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("30-level alias bomb refused in %.3f ms\n", ms);
  // level 5's first alias brings the added nodes from 74 682 to 141 111
  EXPECT_EQ(msg, std::string("test.yaml:6: ") + test::kAliasBombError);
}

TEST(StrictYaml, RefusesTheTwelveLineBombOfTheIssueAndAnyDeeperOne) {
  for (int levels : {5, 10, 11, 100, 1000}) {
    SCOPED_TRACE(levels);
    EXPECT_EQ(error_of([&] { parse(test::alias_bomb(levels)); }), std::string("test.yaml:6: ") + test::kAliasBombError);
  }
}

TEST(StrictYaml, AcceptsABombSmallEnoughToBeAnOrdinaryDocument) {
  // four levels: 74 682 nodes added, under the budget; the tree shares the anchored nodes
  const YAML::Node root = parse(test::alias_bomb(4));
  EXPECT_EQ(root["l4"].size(), 9u);
  EXPECT_EQ(root["l4"][8][8][8][8][8].as<std::string>(), "lol");
}

TEST(StrictYaml, CountsWhatAliasesAddUpToTheBudgetExactly) {
  // a list of 999 scalars is 1000 nodes: each alias of it adds 999
  EXPECT_NO_THROW(parse(repeated_list(999, 100)));  // 99 900 added
  EXPECT_EQ(error_of([] { parse(repeated_list(999, 101)); }),
            "test.yaml:103: uses[100]: aliases add more than 100000 nodes to the document (*block repeats 1000 here): "
            "refused");
  // a large document of its own is no amplification: only what aliases add counts
  EXPECT_NO_THROW(parse(repeated_list(200'000, 0)));
}

TEST(StrictYaml, AcceptsAnchorsOfReasonableSizeAndReadsTheirValuesWhereAliased) {
  const YAML::Node root = parse(
      "gains: &gains {kp: [600, 600, 600], kd: [30, 30, 30]}\n"
      "name: &name arm\n"
      "left: {gains: *gains, label: *name}\n"
      "right: {gains: *gains, label: *name}\n");
  EXPECT_EQ(root["left"]["gains"]["kp"][2].as<int>(), 600);
  EXPECT_EQ(root["right"]["gains"]["kd"][0].as<int>(), 30);
  EXPECT_EQ(root["right"]["label"].as<std::string>(), "arm");
}

TEST(StrictYaml, RefusesAnAliasInsideTheNodeItNames) {
  EXPECT_EQ(error_of([] { parse("a: &x [1, *x]\n"); }),
            "test.yaml:1: a[1]: an alias inside the node it names (the document would be endless)");
}

TEST(StrictYaml, RefusesNestingBeyondTheDepthAlsoThroughAnAlias) {
  // 40 levels anchored at the top, aliased 30 levels down: 70 levels once expanded
  const std::string deep = std::string(40, '[') + "1" + std::string(40, ']');
  const std::string text =
      "deep: &deep " + deep + "\nhere: " + std::string(29, '[') + "*deep" + std::string(29, ']') + "\n";
  const std::string msg = error_of([&] { parse(text); });
  EXPECT_EQ(msg.rfind("test.yaml:2: here", 0), 0u) << msg;
  EXPECT_NE(msg.find(": nested more than 64 levels deep"), std::string::npos) << msg;
  EXPECT_NO_THROW(parse("deep: &deep " + deep + "\nhere: [[*deep]]\n"));
}

TEST(StrictYaml, RefusesADuplicateKeyEvenWhenOneIsAnAlias) {
  // (a space before the colon: `*n:` would be an alias of an anchor called "n:")
  EXPECT_EQ(error_of([] { parse("k: &n name\nm:\n  name: 1\n  *n : 2\n"); }),
            "test.yaml:4: m.name: duplicate key (first given on line 3)");
  EXPECT_EQ(error_of([] { parse("l: &l [a]\nm: {*l : 2}\n"); }),
            "test.yaml:2: m: a key must be a plain name, got a list");
}

TEST(StrictYaml, NamesTheKeyPathBelowTheRootPathOfASetValue) {
  EXPECT_EQ(error_of([] { parse_strict_yaml("{a: 1, a: 2}", "node.yaml (--set x.y={a: 1, a: 2})", "x.y"); }),
            "node.yaml (--set x.y={a: 1, a: 2}):1: x.y.a: duplicate key (first given on line 1)");
}

TEST(StrictYaml, LeavesMalformedYamlToTheCallerEvenAfterAProblem) {
  EXPECT_THROW(parse("a: [1, 2\n"), YAML::ParserException);
  // the parser takes a flow list at the top for a key until it finds the list unterminated
  EXPECT_THROW(parse("[1,"), YAML::ParserException);
  EXPECT_THROW(parse("a: *nowhere\n"), YAML::ParserException);
}

}  // namespace
}  // namespace teleop
