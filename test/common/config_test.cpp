#include "teleop/common/config.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "alias_bomb.h"
#include "teleop/common/joint_config.h"
#include "test_helpers.h"

namespace teleop {
namespace {

constexpr Range kAny{-1e9, 1e9};

ConfigNode load(const std::string& text) { return ConfigNode::load_string(text, "test.yaml"); }

// the message of the ConfigError `f` throws; fails the test when it throws nothing or something else
std::string error_of(const std::function<void()>& f) { return test::error_of<ConfigError>(f); }

using test::TempDir;

// ---- good cases ----

TEST(ConfigNode, ReadsScalarsOfEveryTypeWhenPresent) {
  const ConfigNode c = load("name: arm\nenabled: true\ncount: 42\ngain: 2.5\nneg: -3\n");
  EXPECT_EQ(c.get_string("name"), "arm");
  EXPECT_TRUE(c.get_bool("enabled"));
  EXPECT_EQ(c.get_int("count", Range{0, 100}), 42);
  EXPECT_DOUBLE_EQ(c.get_double("gain", Range{0, 10}), 2.5);
  EXPECT_EQ(c.get_int("neg", Range{-5, 5}), -3);
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigNode, AcceptsValuesOnTheRangeBoundsWhenInclusive) {
  const ConfigNode c = load("lo: 0\nhi: 10\nx: 1.0\n");
  EXPECT_EQ(c.get_int("lo", Range{0, 10}), 0);
  EXPECT_EQ(c.get_int("hi", Range{0, 10}), 10);
  EXPECT_DOUBLE_EQ(c.get_double("x", Range{0, 1}), 1.0);
}

TEST(ConfigNode, ReadsIntegerAsDoubleWhenNumberExpected) {
  const ConfigNode c = load("x: 3\n");
  EXPECT_DOUBLE_EQ(c.get_double("x", kAny), 3.0);
}

TEST(ConfigNode, AppliesDefaultsAndCountsThemAsUsedWhenKeysAbsent) {
  const ConfigNode c = load("present: 1\n");
  EXPECT_EQ(c.get_int("present", kAny), 1);
  EXPECT_EQ(c.get_string("s", "fallback"), "fallback");
  EXPECT_FALSE(c.get_bool("b", false));
  EXPECT_TRUE(c.get_bool("b2", true));
  EXPECT_EQ(c.get_int("i", Range{0, 10}, 7), 7);
  EXPECT_DOUBLE_EQ(c.get_double("d", Range{0, 10}, 0.25), 0.25);
  EXPECT_EQ(c.get_choice("mode", {"a", "b"}, "b"), "b");
  EXPECT_TRUE(c.get_string_list("names").empty());
  EXPECT_TRUE(c.get_double_list("values", kAny).empty());
  EXPECT_TRUE(c.get_node_list("items").empty());
  EXPECT_FALSE(c.optional_child("section").has_value());
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigNode, PrefersPresentValueOverDefaultWhenKeyGiven) {
  const ConfigNode c = load("i: 3\nd: 0.5\ns: given\nb: false\nmode: a\n");
  EXPECT_EQ(c.get_int("i", Range{0, 10}, 7), 3);
  EXPECT_DOUBLE_EQ(c.get_double("d", Range{0, 10}, 0.25), 0.5);
  EXPECT_EQ(c.get_string("s", "fallback"), "given");
  EXPECT_FALSE(c.get_bool("b", true));
  EXPECT_EQ(c.get_choice("mode", {"a", "b"}, "b"), "a");
}

TEST(ConfigNode, BuildsDottedPathWhenNestingChildren) {
  const ConfigNode c = load("a:\n  b:\n    c:\n      value: 5\n");
  const ConfigNode abc = c.child("a").child("b").child("c");
  EXPECT_EQ(c.path(), "");
  EXPECT_EQ(abc.path(), "a.b.c");
  EXPECT_EQ(abc.get_int("value", kAny), 5);
  EXPECT_EQ(abc.file(), "test.yaml");
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigNode, ReadsListsAndNodeListsWhenPresent) {
  const ConfigNode c = load("names: [a, b, c]\nvalues: [1, 2.5, -3]\nitems:\n  - {id: 1}\n  - {id: 2}\n");
  EXPECT_EQ(c.get_string_list("names"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(c.get_double_list("values", kAny), (std::vector<double>{1, 2.5, -3}));
  const auto items = c.get_node_list("items");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].get_int("id", kAny), 1);
  EXPECT_EQ(items[1].get_int("id", kAny), 2);
  EXPECT_EQ(items[1].path(), "items[1]");
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigNode, ListsKeysInFileOrderAndReportsPresence) {
  const ConfigNode c = load("zeta: 1\nalpha: 2\nmid: ~\n");
  EXPECT_EQ(c.keys(), (std::vector<std::string>{"zeta", "alpha", "mid"}));
  EXPECT_TRUE(c.has("zeta"));
  EXPECT_FALSE(c.has("mid"));  // null counts as absent
  EXPECT_FALSE(c.has("nope"));
}

TEST(ConfigNode, ReturnsChildWhenOptionalSectionPresent) {
  const ConfigNode c = load("section:\n  k: v\n");
  const auto s = c.optional_child("section");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->get_string("k"), "v");
  EXPECT_EQ(s->path(), "section");
  EXPECT_NO_THROW(c.check_all_used());
}

TEST(ConfigNode, CountsKeysAsUsedWhenSameSectionIsReadThroughTwoHandles) {
  const ConfigNode c = load("a:\n  x: 1\n  y: 2\n");
  EXPECT_EQ(c.child("a").get_int("x", kAny), 1);
  EXPECT_EQ(c.child("a").get_int("y", kAny), 2);
  EXPECT_NO_THROW(c.check_all_used());
}

// ---- missing keys ----

TEST(ConfigNode, NamesKeyWhenRequiredKeyMissingAtTopLevel) {
  const ConfigNode c = load("a: 1\n");
  EXPECT_EQ(error_of([&] { c.get_int("b", kAny); }), "test.yaml:1: b: missing required key");
  EXPECT_EQ(error_of([&] { c.get_string("s"); }), "test.yaml:1: s: missing required key");
  EXPECT_EQ(error_of([&] { c.get_bool("t"); }), "test.yaml:1: t: missing required key");
  EXPECT_EQ(error_of([&] { c.get_double("d", kAny); }), "test.yaml:1: d: missing required key");
  EXPECT_EQ(error_of([&] { c.child("section"); }), "test.yaml:1: section: missing required key");
}

TEST(ConfigNode, NamesNestedPathAndSectionLineWhenRequiredKeyMissing) {
  const ConfigNode c = load("first: 0\nouter:\n  inner:\n    present: 1\n");
  const ConfigNode inner = c.child("outer").child("inner");
  EXPECT_EQ(error_of([&] { inner.get_int("gone", kAny); }), "test.yaml:4: outer.inner.gone: missing required key");
}

TEST(ConfigNode, ReportsNoValueWhenKeyPresentButEmpty) {
  const ConfigNode c = load("a: 1\nempty:\nb: 2\n");
  EXPECT_EQ(error_of([&] { c.get_int("empty", kAny); }), "test.yaml:2: empty: has no value");
  // a default does not hide a key written without its value
  EXPECT_EQ(error_of([&] { c.get_int("empty", kAny, 3); }), "test.yaml:2: empty: has no value");
}

TEST(ConfigNode, ReportsNoValueAtTheKeysLineWhenEmptyKeyIsLastOrNested) {
  EXPECT_EQ(error_of([] { load("a: 1\nlast:\n").get_string("last"); }), "test.yaml:2: last: has no value");
  const ConfigNode c = load("s:\n  k:\n\n  j: 1\n");
  EXPECT_EQ(error_of([&] { c.child("s").get_double("k", kAny); }), "test.yaml:2: s.k: has no value");
  EXPECT_EQ(error_of([&] { c.child("s").child("k"); }), "test.yaml:2: s.k: has no value");
}

// ---- unknown keys ----

TEST(ConfigNode, ReportsUnknownKeyWithLineWhenTopLevelKeyNeverRead) {
  const ConfigNode c = load("a: 1\nb: 2\ntypo: 3\n");
  c.get_int("a", kAny);
  c.get_int("b", kAny);
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "test.yaml:3: typo: unknown key");
}

TEST(ConfigNode, ReportsUnknownKeyWithNestedPathWhenNestedKeyNeverRead) {
  const ConfigNode c = load("node:\n  name: x\n  rate_hzz: 5\n");
  EXPECT_EQ(c.child("node").get_string("name"), "x");
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "test.yaml:3: node.rate_hzz: unknown key");
}

TEST(ConfigNode, SuggestsTheKnownKeyAMistypedOneIsCloseTo) {
  const ConfigNode c = load("follower:\n  jionts: 7\n");
  const ConfigNode follower = c.child("follower");
  follower.get_int("joints", kAny, 7);
  follower.get_double("command_timeout_ms", kAny, 20.0);
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "test.yaml:2: follower.jionts: unknown key (did you mean 'joints'?)");
}

TEST(ConfigNode, ReportsUnknownSectionWhenWholeSectionNeverRead) {
  const ConfigNode c = load("a: 1\nextra:\n  k: 1\n");
  c.get_int("a", kAny);
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "test.yaml:2: extra: unknown key");
}

TEST(ConfigNode, ReportsUnknownKeyInsideListItemWhenNeverRead) {
  const ConfigNode c = load("items:\n  - id: 1\n    colour: red\n");
  EXPECT_EQ(c.get_node_list("items").at(0).get_int("id", kAny), 1);
  EXPECT_EQ(error_of([&] { c.check_all_used(); }), "test.yaml:3: items[0].colour: unknown key");
}

// ---- wrong types ----

TEST(ConfigNode, RejectsStringWhenNumberExpected) {
  const ConfigNode c = load("rate: fast\ncount: ten\n");
  EXPECT_EQ(error_of([&] { c.get_double("rate", kAny); }), "test.yaml:1: rate: expected a number, got 'fast'");
  EXPECT_EQ(error_of([&] { c.get_int("count", kAny); }), "test.yaml:2: count: expected an integer, got 'ten'");
  // present but wrong is an error even with a default
  EXPECT_EQ(error_of([&] { c.get_double("rate", kAny, 1.0); }), "test.yaml:1: rate: expected a number, got 'fast'");
}

TEST(ConfigNode, RejectsFractionWhenIntegerExpected) {
  const ConfigNode c = load("n: 1.5\n");
  EXPECT_EQ(error_of([&] { c.get_int("n", kAny); }), "test.yaml:1: n: expected an integer, got '1.5'");
}

TEST(ConfigNode, RejectsNonBooleanWhenBoolExpected) {
  const ConfigNode c = load("flag: maybe\n");
  EXPECT_EQ(error_of([&] { c.get_bool("flag"); }), "test.yaml:1: flag: expected true or false, got 'maybe'");
  EXPECT_EQ(error_of([&] { c.get_bool("flag", true); }), "test.yaml:1: flag: expected true or false, got 'maybe'");
}

TEST(ConfigNode, RejectsListWhenScalarExpected) {
  const ConfigNode c = load("x: [1, 2]\ns: [a]\n");
  EXPECT_EQ(error_of([&] { c.get_double("x", kAny); }), "test.yaml:1: x: expected a number, got a list");
  EXPECT_EQ(error_of([&] { c.get_int("x", kAny); }), "test.yaml:1: x: expected an integer, got a list");
  EXPECT_EQ(error_of([&] { c.get_string("s"); }), "test.yaml:2: s: expected a string, got a list");
}

TEST(ConfigNode, RejectsMappingWhenScalarExpected) {
  const ConfigNode c = load("m:\n  k: 1\n");
  EXPECT_EQ(error_of([&] { c.get_string("m"); }), "test.yaml:2: m: expected a string, got a mapping");
}

TEST(ConfigNode, RejectsScalarOrListWhenMappingExpected) {
  const ConfigNode c = load("a: 5\nb: [1]\nouter:\n  c: text\n");
  EXPECT_EQ(error_of([&] { c.child("a"); }), "test.yaml:1: a: expected a mapping, got '5'");
  EXPECT_EQ(error_of([&] { c.child("b"); }), "test.yaml:2: b: expected a mapping, got a list");
  EXPECT_EQ(error_of([&] { c.optional_child("a"); }), "test.yaml:1: a: expected a mapping, got '5'");
  EXPECT_EQ(error_of([&] { c.child("outer").child("c"); }), "test.yaml:4: outer.c: expected a mapping, got 'text'");
}

TEST(ConfigNode, RejectsWrongListShapesWhenListExpected) {
  const ConfigNode c = load("names: abc\nvalues: 3\nitems: {a: 1}\nmixed: [1, x]\nnested: [[a]]\nscalars: [1, 2]\n");
  EXPECT_EQ(error_of([&] { c.get_string_list("names"); }), "test.yaml:1: names: expected a list of strings, got 'abc'");
  EXPECT_EQ(error_of([&] { c.get_double_list("values", kAny); }),
            "test.yaml:2: values: expected a list of numbers, got '3'");
  EXPECT_EQ(error_of([&] { c.get_node_list("items"); }),
            "test.yaml:3: items: expected a list of mappings, got a mapping");
  EXPECT_EQ(error_of([&] { c.get_double_list("mixed", kAny); }), "test.yaml:4: mixed[1]: expected a number, got 'x'");
  EXPECT_EQ(error_of([&] { c.get_string_list("nested"); }), "test.yaml:5: nested[0]: expected a string, got a list");
  EXPECT_EQ(error_of([&] { c.get_node_list("scalars"); }), "test.yaml:6: scalars[0]: expected a mapping, got '1'");
}

// ---- out of range ----

TEST(ConfigNode, RejectsIntegerOutsideRange) {
  const ConfigNode c = load("low: -1\nhigh: 11\n");
  EXPECT_EQ(error_of([&] { c.get_int("low", Range{0, 10}); }), "test.yaml:1: low: value -1 is out of range [0, 10]");
  EXPECT_EQ(error_of([&] { c.get_int("high", Range{0, 10}, 5); }), "test.yaml:2: high: value 11 is out of range [0, 10]");
}

TEST(ConfigNode, RejectsDoubleOutsideRange) {
  const ConfigNode c = load("gain: 1.5\nsmall: 0.0001\n");
  EXPECT_EQ(error_of([&] { c.get_double("gain", Range{0, 1}); }), "test.yaml:1: gain: value 1.5 is out of range [0, 1]");
  EXPECT_EQ(error_of([&] { c.get_double("small", Range{0.001, 0.5}); }),
            "test.yaml:2: small: value 0.0001 is out of range [0.001, 0.5]");
}

TEST(ConfigNode, RejectsNanAndInfinityEvenWhenRangeIsWide) {
  const ConfigNode c = load("a: .nan\nb: .inf\nc: -.inf\nd: .NaN\n");
  constexpr Range kHuge{-1e308, 1e308};
  EXPECT_EQ(error_of([&] { c.get_double("a", kHuge); }), "test.yaml:1: a: value .nan is out of range [-1e+308, 1e+308]");
  EXPECT_EQ(error_of([&] { c.get_double("b", kHuge); }), "test.yaml:2: b: value .inf is out of range [-1e+308, 1e+308]");
  EXPECT_EQ(error_of([&] { c.get_double("c", kHuge); }), "test.yaml:3: c: value -.inf is out of range [-1e+308, 1e+308]");
  EXPECT_EQ(error_of([&] { c.get_double("d", kHuge, 0.0); }),
            "test.yaml:4: d: value .NaN is out of range [-1e+308, 1e+308]");
}

TEST(ConfigNode, RejectsListElementOutsideRangeNamingItsIndex) {
  const ConfigNode c = load("q:\n  - 0.5\n  - 2.0\n");
  EXPECT_EQ(error_of([&] { c.get_double_list("q", Range{0, 1}); }), "test.yaml:3: q[1]: value 2.0 is out of range [0, 1]");
}

TEST(ConfigNode, RejectsNanListElement) {
  const ConfigNode c = load("q: [0.5, .nan]\n");
  EXPECT_EQ(error_of([&] { c.get_double_list("q", kAny); }),
            "test.yaml:1: q[1]: value .nan is out of range [-1e+09, 1e+09]");
}

// ---- choices ----

TEST(ConfigNode, RejectsValueNotAmongChoices) {
  const ConfigNode c = load("mode: turbo\n");
  EXPECT_EQ(error_of([&] { c.get_choice("mode", {"slow", "fast"}); }),
            "test.yaml:1: mode: 'turbo' is not one of: slow, fast");
  EXPECT_EQ(error_of([&] { c.get_choice("mode", {"slow", "fast"}, "slow"); }),
            "test.yaml:1: mode: 'turbo' is not one of: slow, fast");
}

TEST(ConfigNode, AcceptsValueAmongChoices) {
  const ConfigNode c = load("mode: fast\n");
  EXPECT_EQ(c.get_choice("mode", {"slow", "fast"}), "fast");
}

// ---- custom errors ----

TEST(ConfigNode, BuildsErrorAtTheKeysLineWhenAskedForOne) {
  const ConfigNode c = load("a: 1\nsection:\n  lease: 5\n");
  const ConfigNode s = c.child("section");
  EXPECT_EQ(std::string(s.error("lease", "must be longer").what()), "test.yaml:3: section.lease: must be longer");
  // for an absent key the error points at the mapping
  EXPECT_EQ(std::string(s.error("other", "is needed").what()), "test.yaml:3: section.other: is needed");
}

// ---- joint lists (joint_config.h) ----

TEST(ReadJointList, FillsDefaultForEveryJointWhenKeyAbsent) {
  const ConfigNode c = load("x: 1\n");
  const JointVector v = read_joint_list(c, "q", 3, kAny, 0.7);
  EXPECT_DOUBLE_EQ(v[0], 0.7);
  EXPECT_DOUBLE_EQ(v[1], 0.7);
  EXPECT_DOUBLE_EQ(v[2], 0.7);
  EXPECT_DOUBLE_EQ(v[3], 0.0);  // joints beyond the count untouched
}

TEST(ReadJointList, ReadsOneValuePerJointWhenLengthMatches) {
  const ConfigNode c = load("q: [0.1, 0.2, 0.3]\n");
  const JointVector v = read_joint_list(c, "q", 3, kAny, 0.0);
  EXPECT_DOUBLE_EQ(v[0], 0.1);
  EXPECT_DOUBLE_EQ(v[1], 0.2);
  EXPECT_DOUBLE_EQ(v[2], 0.3);
}

TEST(ReadJointList, RejectsListWhenLengthDiffersFromJointCount) {
  const ConfigNode c = load("home:\n  q: [0.1, 0.2]\n  long: [1, 2, 3, 4]\n");
  const ConfigNode home = c.child("home");
  EXPECT_EQ(error_of([&] { read_joint_list(home, "q", 3, kAny, 0.0); }), "test.yaml:2: home.q: has 2 values, expected 3");
  EXPECT_EQ(error_of([&] { read_joint_list(home, "long", 3, kAny, 0.0); }),
            "test.yaml:3: home.long: has 4 values, expected 3");
}

TEST(ReadJointList, RejectsElementOutsideRange) {
  const ConfigNode c = load("q: [0.1, 9.0, 0.3]\n");
  EXPECT_EQ(error_of([&] { read_joint_list(c, "q", 3, Range{-3, 3}, 0.0); }),
            "test.yaml:1: q[1]: value 9.0 is out of range [-3, 3]");
}

TEST(ReadJointCount, RejectsCountOutsideOneToMaxJoints) {
  EXPECT_EQ(read_joint_count(load("joints: 7\n")), 7u);
  EXPECT_EQ(error_of([] { read_joint_count(load("joints: 0\n")); }), "test.yaml:1: joints: value 0 is out of range [1, 32]");
  EXPECT_EQ(error_of([] { read_joint_count(load("joints: 33\n")); }), "test.yaml:1: joints: value 33 is out of range [1, 32]");
}

TEST(ReadJointModel, AppliesDefaultsAndReadsGivenParameters) {
  const ConfigNode c = load("model:\n  inertia_kgm2: 0.5\n  wall_q_rad: 0.8\n");
  const JointModelParams p = read_joint_model(c.child("model"), 4);
  EXPECT_EQ(p.joints, 4u);
  EXPECT_DOUBLE_EQ(p.inertia_kgm2, 0.5);
  EXPECT_DOUBLE_EQ(p.wall_q_rad, 0.8);
  EXPECT_DOUBLE_EQ(p.viscous_nms_per_rad, JointModelParams{}.viscous_nms_per_rad);
  EXPECT_DOUBLE_EQ(p.wall_stiffness_nm_per_rad, JointModelParams{}.wall_stiffness_nm_per_rad);
  EXPECT_NO_THROW(c.check_all_used());
  EXPECT_EQ(error_of([] { read_joint_model(load("model:\n  inertia_kgm2: 0\n").child("model"), 1); }),
            "test.yaml:2: model.inertia_kgm2: value 0 is out of range [0.0001, 100]");
}

// ---- whole documents ----

TEST(ConfigNode, NamesSourceAndLineWhenYamlIsMalformed) {
  const std::string msg = error_of([] { load("a: 1\nb: [1, 2\nc: 3\n"); });
  EXPECT_EQ(msg.rfind("test.yaml:", 0), 0u) << msg;
  EXPECT_NE(msg.find(": malformed YAML: "), std::string::npos) << msg;
  const std::string msg2 = error_of([] { load("a: 1\nb: 2\n  c: 3\n"); });
  EXPECT_EQ(msg2.rfind("test.yaml:3: malformed YAML: ", 0), 0u) << msg2;
}

TEST(ConfigNode, RejectsTopLevelThatIsNotAMapping) {
  EXPECT_EQ(error_of([] { load("- a\n- b\n"); }), "test.yaml: the top level must be a mapping of keys");
  EXPECT_EQ(error_of([] { load("just text\n"); }), "test.yaml: the top level must be a mapping of keys");
  EXPECT_EQ(error_of([] { load(""); }), "test.yaml: the top level must be a mapping of keys");
}

TEST(ConfigNode, LoadsFileAndNamesItInErrors) {
  TempDir dir("teleop_config_test");
  const std::string path = dir.write("node.yaml", "# a comment\nnode:\n  rate_hz: abc\n");
  const ConfigNode c = ConfigNode::load_file(path);
  EXPECT_EQ(c.file(), path);
  EXPECT_EQ(error_of([&] { c.child("node").get_double("rate_hz", kAny); }),
            path + ":3: node.rate_hz: expected a number, got 'abc'");
}

TEST(ConfigNode, NamesFileWhenFileIsMissing) {
  TempDir dir("teleop_config_test");
  const std::string path = dir.path("does_not_exist.yaml");
  EXPECT_EQ(error_of([&] { ConfigNode::load_file(path); }), path + ": cannot open the file");
}

TEST(ConfigNode, NamesFileAndLineWhenFileIsMalformed) {
  TempDir dir("teleop_config_test");
  const std::string path = dir.write("bad.yaml", "a: 1\nb: 2\n  c: 3\n");
  const std::string msg = error_of([&] { ConfigNode::load_file(path); });
  EXPECT_EQ(msg.rfind(path + ":3: malformed YAML: ", 0), 0u) << msg;
}

TEST(ConfigNode, NamesFileWhenFileTopLevelIsNotAMapping) {
  TempDir dir("teleop_config_test");
  const std::string list = dir.write("list.yaml", "- 1\n- 2\n");
  EXPECT_EQ(error_of([&] { ConfigNode::load_file(list); }), list + ": the top level must be a mapping of keys");
  const std::string empty = dir.write("empty.yaml", "");
  EXPECT_EQ(error_of([&] { ConfigNode::load_file(empty); }), empty + ": the top level must be a mapping of keys");
}

// ---- what a file cannot mean (issue 16) ----

TEST(ConfigNode, RejectsAKeyGivenTwiceNamingBothLines) {
  // the first value would win silently and the second would never be range-checked
  EXPECT_EQ(error_of([] { load("follower:\n  command_timeout_ms: 60000\n  command_timeout_ms: 20\n"); }),
            "test.yaml:3: follower.command_timeout_ms: duplicate key (first given on line 2)");
  EXPECT_EQ(error_of([] { load("a: 1\nb: 2\na: 3\n"); }), "test.yaml:3: a: duplicate key (first given on line 1)");
}

TEST(ConfigNode, RejectsAKeyGivenTwiceInsideAListItem) {
  EXPECT_EQ(error_of([] { load("runs:\n  - name: a\n    name: b\n"); }),
            "test.yaml:3: runs[0].name: duplicate key (first given on line 2)");
}

TEST(ConfigNode, RejectsAKeyThatIsNotAPlainName) {
  EXPECT_EQ(error_of([] { load("node:\n  [a, b]: 1\n"); }), "test.yaml:2: node: a key must be a plain name, got a list");
  EXPECT_EQ(error_of([] { load("? {a: 1}\n: 2\n"); }), "test.yaml:1: (top level): a key must be a plain name, got a mapping");
}

TEST(ConfigNode, RejectsADuplicateOrNonScalarKeyInAnOverride) {
  ConfigNode c = load("node: {}\n");
  EXPECT_EQ(error_of([&] { c.apply_override("node={a: 1, a: 2}"); }),
            "test.yaml (--set node={a: 1, a: 2}):1: node.a: duplicate key (first given on line 1)");
}

TEST(ConfigNode, RefusesAnAliasBombInAFileNamingTheFileAndTheAlias) {
  TempDir dir("teleop_config_test");
  const std::string path = dir.write("bomb.yaml", test::alias_bomb(11));
  EXPECT_EQ(error_of([&] { ConfigNode::load_file(path); }), path + ":6: " + test::kAliasBombError);
}

TEST(ConfigNode, RefusesAPathToSomethingElseThanARegularFile) {
  TempDir dir("teleop_config_test");
  const ConfigNode c = load("model: /dev/null\nfolder: " + dir.path("") + "\n");
  EXPECT_EQ(error_of([&] { c.get_path("model"); }),
            "test.yaml:1: model: /dev/null is not a regular file (a folder, FIFO or device)");
  EXPECT_NE(error_of([&] { c.get_path("folder"); }).find(" is not a regular file"), std::string::npos);
}

TEST(ConfigNode, NamesTheFolderWhenAFolderIsGivenAsTheFile) {
  TempDir dir("teleop_config_test");
  EXPECT_EQ(error_of([&] { ConfigNode::load_file(dir.path("")); }),
            dir.path("") + ": is a folder, not a configuration file");
}

TEST(ConfigNode, ReadsABoundOrOffAndRefusesAZeroThatWouldSwitchTheCheckOff) {
  const ConfigNode c = load("a: 500\nb: off\nc: 0\nd: -3\ne: x\n");
  constexpr Range kPositive{1, 60'000};
  EXPECT_EQ(c.get_bound_or_off("a", kPositive, 7), 500.0);
  EXPECT_TRUE(std::isinf(c.get_bound_or_off("b", kPositive, 7)));
  EXPECT_EQ(c.get_bound_or_off("absent", kPositive, 7), 7.0);
  EXPECT_EQ(error_of([&] { c.get_bound_or_off("c", kPositive, 7); }),
            "test.yaml:3: c: 0 would switch the check off: write off if that is meant");
  EXPECT_EQ(error_of([&] { c.get_bound_or_off("d", kPositive, 7); }), "test.yaml:4: d: value -3 is out of range [1, 60000]");
  EXPECT_EQ(error_of([&] { c.get_bound_or_off("e", kPositive, 7); }), "test.yaml:5: e: expected a number or off, got 'x'");
  c.check_all_used();
}

}  // namespace
}  // namespace teleop
