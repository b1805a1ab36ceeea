// Each node executable as a real process: bad input stops it before it starts, with one line
// naming file, key and problem; signals stop it cleanly.
#include <gtest/gtest.h>

#include <csignal>
#include <regex>

#include "process_helpers.h"
#include "teleop/common/version.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

struct BadConfigCase {
  const char* name;
  const char* from;      // text in the shipped config ...
  const char* to;        // ... replaced by this
  const char* expected;  // the error names this key and problem
};

const BadConfigCase kBadConfigs[] = {
    {"missing_key", "  joints: 7\n", "", ": missing required key"},
    {"unknown_key", "  joints: 7\n", "  joints: 7\n  jionts: 7\n", ".jionts: unknown key"},
    {"wrong_type", "  rate_hz: 1000\n", "  rate_hz: fast\n", "node.rate_hz: expected a number, got 'fast'"},
    {"out_of_range", "  rate_hz: 1000\n", "  rate_hz: 0\n", "node.rate_hz: value 0 is out of range [1, 10000]"},
    {"not_a_mapping", "transport:\n", "transport: udp\nunused:\n", "transport: expected a mapping, got 'udp'"},
    {"bad_peer", "  initial_peers: []", "  initial_peers: [\"10.0.0.300\"]", "transport.initial_peers: '10.0.0.300'"},
    // a second value would win nothing and never be range-checked (issue 16)
    {"duplicate_key", "  rate_hz: 1000\n", "  rate_hz: 1000\n  rate_hz: 5\n",
     "node.rate_hz: duplicate key (first given on line"},
    {"key_not_a_name", "  rate_hz: 1000\n", "  rate_hz: 1000\n  [a, b]: 1\n",
     "node: a key must be a plain name, got a list"},
};

class NodeProcess : public ::testing::TestWithParam<const char*> {
 protected:
  std::string node() const { return GetParam(); }
  std::string executable() const { return bin("teleop_" + node()); }
  std::string shipped_config() const { return source("config/nodes/" + node() + ".yaml"); }
};

TEST_P(NodeProcess, StopsBeforeStartingOnEachKindOfBadConfig) {
  const std::string dir = make_temp_dir();
  std::string original = read_file(shipped_config());
  // the copies live in a temporary folder: paths relative to config/nodes must still resolve
  for (size_t at = original.find("../models/"); at != std::string::npos; at = original.find("../models/", at)) {
    original.replace(at, 10, source("config/models/"));
  }
  for (const auto& bad : kBadConfigs) {
    SCOPED_TRACE(bad.name);
    const auto at = original.find(bad.from);
    ASSERT_NE(at, std::string::npos) << "the shipped config changed; update this test";
    std::string text = original;
    text.replace(at, std::string(bad.from).size(), bad.to);
    const std::string path = dir + "/" + bad.name + ".yaml";
    write_file(path, text);

    const ProcessResult r = run_process({executable(), "--config", path}, std::chrono::seconds(20));
    EXPECT_EQ(r.exit_status, 2) << r.output;
    // exactly one error line: "config error: <file>:<line>: <key>: <problem>"
    const std::regex line_re("config error: " + path + ":[0-9]+: [a-z_.]*" + "[^\\n]*");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, line_re)) << r.output;
    EXPECT_NE(m.str().find(bad.expected), std::string::npos) << m.str();
    EXPECT_EQ(r.output.find("starting"), std::string::npos) << "must fail before joining the network";
  }
}

TEST_P(NodeProcess, RejectsAMissingConfigFile) {
  const ProcessResult r = run_process({executable(), "--config", "/nonexistent/x.yaml"}, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/x.yaml: cannot open the file"), std::string::npos) << r.output;
}

TEST_P(NodeProcess, RejectsAFolderAsConfigNamingIt) {
  const std::string dir = make_temp_dir();
  const ProcessResult r = run_process({executable(), "--config", dir}, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find(dir + ": is a folder, not a configuration file"), std::string::npos) << r.output;
}

// numbers that configure nothing a run can be: each is refused before the node starts (issue 16:
// --duration nan ran forever, 1e300 ended after one cycle with rc 0, --trace-seconds 1e300 kept
// one row, --duration 1e6 with --trace died of bad_alloc after joining the network)
TEST_P(NodeProcess, RejectsNumericFlagsThatConfigureNothing) {
  const std::string trace = make_temp_dir() + "/t.csv";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--duration", "nan"}, "--duration: must be a finite number in [0, 1000000], got nan"},
      {{"--duration", "inf"}, "--duration: must be a finite number"},
      {{"--duration", "1e300"}, "--duration: must be a finite number"},
      {{"--duration", "-1"}, "--duration: must be a finite number"},
      {{"--trace", trace, "--trace-seconds", "1e300"}, "--trace-seconds: must be a finite number"},
      {{"--duration", "1e6", "--trace", trace}, "--trace-seconds: a trace of"},
  };
  for (const auto& [flags, expected] : cases) {
    std::vector<std::string> argv{executable(), "--config", shipped_config()};
    argv.insert(argv.end(), flags.begin(), flags.end());
    const ProcessResult r = run_process(argv, std::chrono::seconds(20));
    SCOPED_TRACE(flags.front() + " " + flags[1]);
    EXPECT_EQ(r.exit_status, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("starting"), std::string::npos) << "must fail before joining the network";
  }
}

TEST_P(NodeProcess, RejectsUnknownFlags) {
  const ProcessResult r =
      run_process({executable(), "--config", shipped_config(), "--frobnicate"}, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_NE(r.output.find("--frobnicate"), std::string::npos) << r.output;
}

TEST_P(NodeProcess, PrintsHelp) {
  const ProcessResult r = run_process({executable(), "--help"}, std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("--config"), std::string::npos) << r.output;
}

TEST_P(NodeProcess, ShutsDownCleanlyOnSigtermAndSigint) {
  for (int sig : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(sig);
    const std::string report = make_temp_dir() + "/report.yaml";
    RunningProcess p(
        {executable(), "--config", shipped_config(), "--domain", std::to_string(unique_domain()), "--report", report});
    ASSERT_TRUE(p.wait_for_output("starting", std::chrono::seconds(20))) << p.output();
    p.run_for(std::chrono::milliseconds(500));
    // a generous bound only to catch a hang; the time itself is measured and reported, not asserted
    EXPECT_EQ(p.stop(sig, std::chrono::seconds(10)), 0) << p.output();
    const runtime::NodeReport r = runtime::read_report(report);
    EXPECT_GE(r.shutdown_ms, 0.0);
    EXPECT_GT(r.cycles, 100u) << "the loop ran before the signal";
    std::printf("%s: shutdown %.1f ms after signal %d\n", node().c_str(), r.shutdown_ms, sig);
  }
}

INSTANTIATE_TEST_SUITE_P(Nodes, NodeProcess, ::testing::Values("leader", "follower", "twin"));

// the follower's own: a model MuJoCo cannot load is found while reading the config, before the
// participant joins; a 0 that would switch a safety check off is refused
TEST(FollowerConfigProcess, RefusesAModelThatDoesNotLoadAndAZeroThatSwitchesACheckOff) {
  const std::string dir = make_temp_dir();
  write_file(dir + "/broken.xml", "<mujoco><worldbody><body></mujoco>\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"follower.mujoco.model=" + dir + "/broken.xml", "follower.mujoco.model: the model does not load: "},
      {"follower.max_command_age_ms=0", "follower.max_command_age_ms: 0 would switch the check off: write off"},
      {"follower.max_torque_rate_nm_per_s=0", "follower.max_torque_rate_nm_per_s: 0 would switch the check off"},
  };
  for (const auto& [set, expected] : cases) {
    SCOPED_TRACE(set);
    const ProcessResult r =
        run_process({bin("teleop_follower"), "--config", source("config/nodes/follower.yaml"), "--set", set},
                    std::chrono::seconds(20));
    EXPECT_EQ(r.exit_status, 2) << r.output;
    EXPECT_NE(
        r.output.find("config error: " + source("config/nodes/follower.yaml") + " (--set " + set + "): " + expected),
        std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("starting"), std::string::npos) << "must fail before joining the network";
  }
}

TEST(Version, EveryExecutablePrintsTheProjectVersionAndItsGitDescription) {
  for (const char* exe :
       {"teleop", "teleop_leader", "teleop_follower", "teleop_twin", "teleop_hand", "teleop_hand_emulator",
        "teleop_twin_sweep", "teleop_box_plan", "teleop_lockstep_controller"}) {
    SCOPED_TRACE(exe);
    const ProcessResult r = run_process({bin(exe), "--version"}, std::chrono::seconds(10));
    EXPECT_EQ(r.exit_status, 0) << r.output;
    EXPECT_EQ(r.output, version_text() + "\n");
    EXPECT_TRUE(std::regex_match(version_text(), std::regex(R"(teleop [0-9]+\.[0-9]+\.[0-9]+ \(git .+\))")))
        << version_text();
  }
}

TEST(DidYouMean, AMistypedSubcommandFlagOrConfigKeyIsNamedWithTheNearestKnownOne) {
  const ProcessResult command = run_process({bin("teleop"), "lauch", "demo.yaml"}, std::chrono::seconds(10));
  EXPECT_EQ(command.exit_status, 2);
  EXPECT_NE(command.output.find("'lauch' is not a command of teleop (did you mean 'launch'?)"), std::string::npos)
      << command.output;
  const ProcessResult flag = run_process(
      {bin("teleop_follower"), "-c", source("config/nodes/follower.yaml"), "--duraton", "1"}, std::chrono::seconds(10));
  EXPECT_EQ(flag.exit_status, 2);
  EXPECT_NE(flag.output.find("(did you mean '--duration'?)"), std::string::npos) << flag.output;
  const ProcessResult key = run_process({bin("teleop_follower"), "-c", source("config/nodes/follower.yaml"), "--set",
                                         "follower.command_timeuot_ms=20", "--duration", "1"},
                                        std::chrono::seconds(10));
  EXPECT_EQ(key.exit_status, 2);
  EXPECT_NE(key.output.find("follower.command_timeuot_ms: unknown key (did you mean 'command_timeout_ms'?)"),
            std::string::npos)
      << key.output;
}

TEST(BadChoice, AValueNotAmongAnOptionsChoicesIsNamedWithThem) {
  const ProcessResult storage = run_process({bin("teleop"), "record", "-o", make_temp_dir() + "/r", "--storage", "sqlite"},
                                            std::chrono::seconds(10));
  EXPECT_EQ(storage.exit_status, 2);
  EXPECT_NE(storage.output.find("--storage: 'sqlite' is not one of mcap, sqlite3"), std::string::npos) << storage.output;
  const ProcessResult compression = run_process(
      {bin("teleop"), "record", "-o", make_temp_dir() + "/r.mcap", "--compression", "bzip2"}, std::chrono::seconds(10));
  EXPECT_EQ(compression.exit_status, 2);
  EXPECT_NE(compression.output.find("--compression: 'bzip2' is not one of zstd, lz4, none"), std::string::npos)
      << compression.output;
}

}  // namespace
}  // namespace teleop::test
