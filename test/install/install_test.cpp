// The install as a user gets it: `cmake --install` of this build into a fresh prefix outside the
// tree, then a program of its own (consumer/, find_package(teleop 0.1)) built against that prefix
// only, streaming joint commands to the INSTALLED follower, which is started by its config's name
// and must find that config, its model and its libraries in the prefix (docs/install.md).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "process_helpers.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

// runs a step, prints its wall time (the test has a budget: < 60 s in CI) and fails with its output
ProcessResult step(const std::string& what, const std::vector<std::string>& argv, std::chrono::seconds timeout) {
  const auto start = std::chrono::steady_clock::now();
  ProcessResult r = run_process(argv, timeout);
  std::printf("%-28s %5.1f s\n", what.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  EXPECT_EQ(r.exit_status, 0) << what << ":\n" << r.output;
  return r;
}

// the files of the teleop libraries a running process has mapped
std::set<std::string> mapped_teleop_libraries(pid_t pid) {
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  std::set<std::string> files;
  for (std::string line; std::getline(maps, line);) {
    const auto slash = line.find('/');
    if (slash != std::string::npos && line.find("/libteleop_") != std::string::npos) files.insert(line.substr(slash));
  }
  return files;
}

// A tree that built only some installed targets (the demo's build/demo): moves one aside for the
// test's duration (the test runs alone: SERIAL) and puts it back
class MissingBuildOutput {
 public:
  explicit MissingBuildOutput(fs::path file) : file_(std::move(file)), aside_(file_.string() + ".aside") {
    fs::rename(file_, aside_);
  }
  ~MissingBuildOutput() { fs::rename(aside_, file_); }
  MissingBuildOutput(const MissingBuildOutput&) = delete;
  MissingBuildOutput& operator=(const MissingBuildOutput&) = delete;

 private:
  fs::path file_;
  fs::path aside_;
};

TEST(Install, FromATreeLackingAnInstalledTargetCopiesNothingAndSaysWhatToBuild) {
  const fs::path prefix = fs::path(make_temp_dir()) / "prefix";
  ProcessResult r;
  {
    const MissingBuildOutput missing(fs::path(TELEOP_BUILD_DIR) / "bin/teleop_hand");
    r = run_process({TELEOP_CMAKE_COMMAND, "--install", TELEOP_BUILD_DIR, "--prefix", prefix.string()}, 120s);
  }
  EXPECT_NE(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("lacks installed targets (teleop_hand)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--target teleop_installables"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(prefix)) << "nothing was copied";
}

TEST(Install, AConsumerBuiltAgainstTheInstallDrivesTheInstalledFollower) {
  const fs::path tmp = make_temp_dir();
  const fs::path prefix = tmp / "prefix";
  step("cmake --install", {TELEOP_CMAKE_COMMAND, "--install", TELEOP_BUILD_DIR, "--prefix", prefix.string()}, 120s);
  ASSERT_FALSE(HasFailure());

  // what a user looks for first
  for (const char* file : {"bin/teleop", "bin/teleop_follower", "lib/cmake/teleop/teleopConfig.cmake",
                           "lib/cmake/teleop/teleopConfigVersion.cmake", "include/teleop/msg/arm.h",
                           "include/teleop/transport/participant.h", "share/teleop/config/scenarios/demo.yaml",
                           "share/teleop/config/models/generated/panda_chain.xml", "share/teleop/idl/arm.idl",
                           "share/teleop/teleop_plot/__main__.py"}) {
    EXPECT_TRUE(fs::is_regular_file(prefix / file)) << file;
  }
  const ProcessResult version = step("teleop --version", {(prefix / "bin/teleop").string(), "--version"}, 20s);
  EXPECT_NE(version.output.find(std::string("teleop ") + TELEOP_VERSION_STRING + " (git "), std::string::npos)
      << version.output;

  // an installed executable looks for names in its own prefix first, the source tree after it
  const ProcessResult unknown =
      run_process({(prefix / "bin/teleop_follower").string(), "--config", "no_such_node"}, 20s);
  EXPECT_EQ(unknown.exit_status, 2) << unknown.output;
  const auto installed_dir = unknown.output.find((prefix / "share/teleop/config/nodes").string());
  EXPECT_NE(installed_dir, std::string::npos) << unknown.output;
  EXPECT_LT(installed_dir, unknown.output.find(TELEOP_SOURCE_DIR)) << unknown.output;

  // a project of its own against the prefix only (ccache keyed on paths relative to tmp, so that
  // a rerun compiles nothing)
  const fs::path consumer = tmp / "consumer";
  std::vector<std::string> configure{TELEOP_CMAKE_COMMAND,
                                     "-S",
                                     TELEOP_CONSUMER_DIR,
                                     "-B",
                                     consumer.string(),
                                     "-G",
                                     TELEOP_CMAKE_GENERATOR,
                                     "-DCMAKE_MAKE_PROGRAM=" TELEOP_MAKE_PROGRAM,
                                     "-DCMAKE_CXX_COMPILER=" TELEOP_CXX_COMPILER,
                                     "-DCMAKE_PREFIX_PATH=" + prefix.string()};
  if (!std::string(TELEOP_CCACHE).empty()) configure.push_back("-DCMAKE_CXX_COMPILER_LAUNCHER=" TELEOP_CCACHE);
  const ProcessResult configured = step("consumer: configure", configure, 120s);
  EXPECT_NE(configured.output.find("teleop " TELEOP_VERSION_STRING " in " + (prefix / "lib/cmake/teleop").string()),
            std::string::npos)
      << configured.output;
  step("consumer: build",
       {TELEOP_CMAKE_COMMAND, "-E", "env", "CCACHE_BASEDIR=" + tmp.string(), TELEOP_CMAKE_COMMAND, "--build",
        consumer.string()},
       180s);
  ASSERT_FALSE(HasFailure());

  // the installed follower by its config's name; its model path is relative to that config
  const int domain = unique_domain();
  const fs::path report = tmp / "follower.yaml";
  const auto start = std::chrono::steady_clock::now();
  // the shipped follower takes commands from the leader and the twin only: the consumer is named
  RunningProcess follower({(prefix / "bin/teleop_follower").string(), "--config", "follower", "--domain",
                           std::to_string(domain), "--report", report.string(), "--set",
                           "follower.accept_commands_from=[consumer]"});
  const ProcessResult consumed =
      run_process({(consumer / "teleop_consumer").string(), std::to_string(domain), "2"}, 40s);
  follower.run_for(10ms);
  if (TELEOP_SHARED_LIBS) {
    // the libraries it runs on are the installed ones (RPATH $ORIGIN/../lib), not the build's
    const std::set<std::string> libraries = mapped_teleop_libraries(follower.process().pid());
    EXPECT_FALSE(libraries.empty());
    for (const std::string& library : libraries) EXPECT_EQ(library.rfind((prefix / "lib").string(), 0), 0u) << library;
  }
  EXPECT_EQ(follower.stop(SIGINT, 10s), 0) << follower.output();
  std::printf("%-28s %5.1f s\n", "follower + consumer",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  ASSERT_EQ(consumed.exit_status, 0) << consumed.output << follower.output();
  std::smatch sent;
  ASSERT_TRUE(std::regex_search(consumed.output, sent, std::regex("sent ([0-9]+) commands"))) << consumed.output;
  const double commands = std::stod(sent[1]);

  const runtime::NodeReport r = runtime::read_report(report.string());
  bool found = false;
  for (const runtime::ReceivedTopic& t : r.received) {
    if (t.topic != "teleop/leader/joint_command") continue;
    found = true;
    std::printf("the follower received %llu of them\n", static_cast<unsigned long long>(t.received));
    // best-effort 1 kHz stream on one host: nearly all arrive; half is a bound no loaded VM misses
    EXPECT_GT(static_cast<double>(t.received), 0.5 * commands) << t.received << " of " << commands;
    EXPECT_LE(static_cast<double>(t.received), commands);
  }
  EXPECT_TRUE(found) << "the follower's report has no teleop/leader/joint_command";
  std::printf("the installed follower received the consumer's commands: %s\n", consumed.output.c_str());
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace teleop::test
