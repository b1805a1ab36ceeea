// Configs that cannot hurt (issue 28): what a hostile tester gave the node executables, as real
// processes. An alias bomb, a FIFO as the config, an unwritable --trace or --report are refused
// before the node joins the network (exit 2, naming the file); a signal while a large config is
// parsed ends the node at once; a trace onto a full device is logged when the first write fails
// and the report counts every row that never reached the file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include "alias_bomb.h"
#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

const char* const kNodes[] = {"leader", "follower", "twin"};

// the bound from the process's start to its exit; a sanitizer build's process needs
// 0.4-0.9 s here only to start (its shadow memory, its static libraries)
#ifdef TELEOP_SANITIZED
constexpr std::chrono::seconds kBombExitBound{6};
#else
constexpr std::chrono::seconds kBombExitBound{2};
#endif

TEST(HostileConfig, AnAliasBombIsRefusedWithinTwoSecondsNamingTheFile) {
  const std::string path = make_temp_dir() + "/bomb.yaml";
  // the tester's 12 lines: 9^12 scalars to anything that expands them, hours of a tree walk
  write_file(path, alias_bomb(11));
  for (const char* node : kNodes) {
    SCOPED_TRACE(node);
    const auto start = Clock::now();
    const ProcessResult r = run_process({bin(std::string("teleop_") + node), "--config", path}, kBombExitBound);
    const double ms = ms_since(start);
    ASSERT_EQ(r.exit_status, 2) << "not refused within " << kBombExitBound.count() << " s\n" << r.output;
    EXPECT_NE(r.output.find("config error: " + path + ":6: " + kAliasBombError), std::string::npos) << r.output;
    std::printf("%s: the alias bomb refused, process ended %.0f ms after its start\n", node, ms);
  }
}

TEST(HostileConfig, AFifoAsTheConfigIsRefusedWithoutWaitingForAWriter) {
  const std::string fifo = make_temp_dir() + "/config.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const char* node : kNodes) {
    SCOPED_TRACE(node);
    const ProcessResult r =
        run_process({bin(std::string("teleop_") + node), "--config", fifo}, std::chrono::seconds(10));
    EXPECT_EQ(r.exit_status, 2) << r.output;
    EXPECT_NE(r.output.find("config error: " + fifo + ": is a FIFO (named pipe), not a regular file"),
              std::string::npos)
        << r.output;
  }
}

// the shipped follower config and, after it, a section of `entries` lines nobody reads: legal YAML
// that takes seconds to parse (100 000 entries, 4.7 MB: about 4 s here), and would then be refused
// as unknown keys
std::string large_config(const std::string& dir, int entries) {
  std::string text = read_file(config_copy(dir, "follower.yaml", {}));
  text.reserve(text.size() + static_cast<size_t>(entries) * 48);
  text += "padding:\n";
  for (int i = 0; i < entries; ++i) text += "  entry_" + std::to_string(i) + ": [1.5, 2.5, 3.5, 4.5, 5.5, 6.5]\n";
  const std::string path = dir + "/large.yaml";
  write_file(path, text);
  return path;
}

// the bound; a sanitizer build's process takes longer to tear down (its shadow memory:
// 27-93 ms measured on this VM under load, against 7-13 ms in the default build)
#ifdef TELEOP_SANITIZED
constexpr double kParseExitBoundMs = 300.0;
#else
constexpr double kParseExitBoundMs = 100.0;
#endif

TEST(HostileConfig, SigtermWhileAConfigIsParsedEndsTheNodeAtOnce) {
  const std::string config = large_config(make_temp_dir(), 100'000);
  for (const int sig : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(sig);
    RunningProcess p({bin("teleop_follower"), "--config", config, "--log-level", "debug"});
    ASSERT_TRUE(p.wait_for_output("reading the configuration", std::chrono::seconds(20))) << p.output();
    // well into the parse, which takes seconds
    p.run_for(std::chrono::milliseconds(300));
    const auto signalled = Clock::now();
    p.process().signal(sig);
    const std::optional<int> status = p.process().wait_for(10'000);
    const double ms = ms_since(signalled);
    p.run_for(std::chrono::milliseconds(10));
    ASSERT_EQ(status, 128 + sig) << p.output();
    EXPECT_NE(p.output().find("stopped by a signal before joining the network"), std::string::npos) << p.output();
    EXPECT_EQ(p.output().find("config error"), std::string::npos) << "the parse had ended before the signal";
    EXPECT_EQ(p.output().find("starting"), std::string::npos) << p.output();
    std::printf("follower: signal %d during the config's parse, exit %.1f ms after it\n", sig, ms);
    // the handler exits at once; the rest is the kernel's teardown and this test's 2 ms polls
    EXPECT_LT(ms, kParseExitBoundMs);
  }
}

// once the participant exists a signal raises the flag: the node leaves the network cleanly (the
// participant deleted, the report written), whatever it was doing; the time is measured, the issue's
// bound asserted only for the parse (the follower's logic may take its model's build time here)
TEST(HostileConfig, ASignalWhileTheNodeJoinsTheNetworkEndsItCleanly) {
  for (const char* node : kNodes) {
    SCOPED_TRACE(node);
    const std::string report = make_temp_dir() + "/report.yaml";
    RunningProcess p({bin(std::string("teleop_") + node), "--config", node, "--domain", std::to_string(unique_domain()),
                      "--report", report});
    // printed right after the participant's creation, before the logic is built
    ASSERT_TRUE(p.wait_for_output("QoS profiles from", std::chrono::seconds(20))) << p.output();
    const auto signalled = Clock::now();
    p.process().signal(SIGTERM);
    const std::optional<int> status = p.process().wait_for(10'000);
    const double ms = ms_since(signalled);
    p.run_for(std::chrono::milliseconds(10));
    ASSERT_EQ(status, 0) << p.output();
    const runtime::NodeReport r = runtime::read_report(report);
    EXPECT_GE(r.shutdown_ms, 0.0);
    std::printf(
        "%s: SIGTERM while joining the network: left it %.1f ms after the signal (%llu cycles), process "
        "exit after %.1f ms\n",
        node, r.shutdown_ms, static_cast<unsigned long long>(r.cycles), ms);
  }
}

TEST(HostileConfig, AnUnwritableTraceOrReportFailsBeforeJoiningTheNetwork) {
  const std::string dir = make_temp_dir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--trace", "/nonexistent/dir/t.csv"}, {"--report", "/nonexistent/dir/r.yaml"}, {"--trace", dir},  // a folder
  };
  for (const auto& [flag, path] : cases) {
    SCOPED_TRACE(flag + " " + path);
    const ProcessResult r = run_process(
        {bin("teleop_follower"), "--config", source("config/nodes/follower.yaml"), "--duration", "1", flag, path},
        std::chrono::seconds(20));
    EXPECT_EQ(r.exit_status, 2) << r.output;
    EXPECT_NE(r.output.find("config error: " + flag + " " + path + ": cannot be written: "), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("starting"), std::string::npos) << "must fail before joining the network";
  }
  // the check leaves no file behind
  const ProcessResult r = run_process({bin("teleop_follower"), "--config", source("config/nodes/follower.yaml"),
                                       "--trace", dir + "/t.csv", "--report", "/nonexistent/r.yaml"},
                                      std::chrono::seconds(20));
  EXPECT_EQ(r.exit_status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/t.csv"));
}

// a node's trace onto /dev/full: every write refused, as on a full disk
struct FullDeviceRun {
  ProcessResult result;
  runtime::NodeReport report;
  bool failure_logged_while_running = false;
};

FullDeviceRun trace_onto_a_full_device(bool stream) {
  const std::string report = make_temp_dir() + "/report.yaml";
  std::vector<std::string> argv{bin("teleop_follower"),
                                "--config",
                                source("config/nodes/follower.yaml"),
                                "--domain",
                                std::to_string(unique_domain()),
                                "--duration",
                                "2",
                                "--trace",
                                "/dev/full",
                                "--report",
                                report};
  if (stream) argv.emplace_back("--trace-stream");
  RunningProcess p(argv);
  FullDeviceRun run;
  run.failure_logged_while_running =
      p.wait_for_output("trace /dev/full: write failed (No space left on device)", std::chrono::seconds(20)) &&
      p.output().find("cycles at") == std::string::npos;
  run.result.exit_status = p.process().wait_for(20'000);
  p.run_for(std::chrono::milliseconds(10));
  run.result.output = p.output();
  run.report = runtime::read_report(report);
  return run;
}

// one row per cycle the loop ran, none in the file; the report's cycles count the pacer's ticks,
// and the tick at the end of the duration ends the loop without a cycle (nor a row)
void expect_every_row_dropped(const runtime::NodeReport& report) {
  const double dropped = counter(report, "trace_rows_dropped");
  EXPECT_GE(dropped, static_cast<double>(report.cycles - 1));
  EXPECT_LE(dropped, static_cast<double>(report.cycles));
}

TEST(HostileConfig, AStreamedTraceOntoAFullDeviceIsLoggedWhenItFailsAndCountedInTheReport) {
  const FullDeviceRun run = trace_onto_a_full_device(true);
  // logged by the trace's writer within its first period, while the loop runs on
  EXPECT_TRUE(run.failure_logged_while_running) << run.result.output;
  // the run's results are whole; the trace is not: exit 1
  EXPECT_EQ(run.result.exit_status, 1) << run.result.output;
  EXPECT_GT(run.report.cycles, 100u);
  EXPECT_EQ(counter(run.report, "trace_rows_written"), 0.0);
  expect_every_row_dropped(run.report);
}

TEST(HostileConfig, ATraceWrittenAtExitOntoAFullDeviceIsLoggedAndCountedInTheReport) {
  const FullDeviceRun run = trace_onto_a_full_device(false);
  EXPECT_EQ(run.result.exit_status, 1) << run.result.output;
  EXPECT_NE(run.result.output.find("trace /dev/full: write failed (No space left on device)"), std::string::npos)
      << run.result.output;
  EXPECT_EQ(counter(run.report, "trace_rows_written"), 0.0);
  expect_every_row_dropped(run.report);
}

}  // namespace
}  // namespace teleop::test
