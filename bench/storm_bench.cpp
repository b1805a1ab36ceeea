// The follower's loop under the storm of issue 28 against the same run quiet, in one sitting:
// lateness, skipped deadlines, holds and the longest write, per run. Needs root (network
// namespaces). Two shared cores measure CPU contention as much as the design: compare the rows
// of one sitting, never a number across machines. docs/benchmarks.md has a run and its command.
//   teleop_storm_bench [--repeats N] [--seconds S] [--realtime off|optional|required]
#include <CLI/CLI.hpp>

#include <cstdio>

#include "netns_network.h"
#include "storm.h"

namespace {

using namespace teleop;

double counter_of(const runtime::NodeReport& r, const char* name) {
  for (const auto& [key, value] : r.counters) {
    if (key == name) return value;
  }
  return -1;
}

int64_t longest_write_ns(const runtime::NodeReport& r) {
  int64_t longest = 0;
  for (const auto& p : r.published) longest = std::max(longest, p.write_max_ns);
  return longest;
}

int64_t write_p99_ns(const runtime::NodeReport& r, const std::string& topic) {
  for (const auto& p : r.published) {
    if (p.topic == topic) return p.write_p99_ns;
  }
  return -1;
}

void print_row(const char* run, const test::StormResult& r) {
  const auto& f = r.follower;
  std::printf("%-6s %9.1f %9.1f %10.1f %8llu %6.0f %8.0f %10.1f %10.1f %7d\n", run, f.lateness_p50_ns * 1e-3,
              f.lateness_p99_ns * 1e-3, f.lateness_max_ns * 1e-3, static_cast<unsigned long long>(f.skipped),
              counter_of(f, "stall_holds"), counter_of(f, "watchdog_trips"),
              write_p99_ns(f, "teleop/follower/joint_state") * 1e-3, longest_write_ns(f) * 1e-3, r.churn_rounds);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"the follower's loop under a storm of readers and joining participants, against quiet"};
  int repeats = 3;
  test::StormOptions options;
  app.add_option("--repeats", repeats, "quiet/storm pairs")->check(CLI::Range(1, 100));
  app.add_option("--seconds", options.seconds, "length of each run")->check(CLI::Range(5.0, 600.0));
  app.add_option("--realtime", options.realtime, "the nodes' node.realtime")
      ->check(CLI::IsMember({"off", "optional", "required"}));
  CLI11_PARSE(app, argc, argv);
  if (const std::string reason = test::netns_unavailable_reason(); !reason.empty()) {
    std::fprintf(stderr, "storm_bench: %s\n", reason.c_str());
    return 2;
  }
  std::printf("%-6s %9s %9s %10s %8s %6s %8s %10s %10s %7s\n", "run", "late_p50", "late_p99", "late_max", "skipped",
              "stalls", "watchdog", "write_p99", "write_max", "rounds");
  std::printf("%-6s %9s %9s %10s %8s %6s %8s %10s %10s %7s\n", "", "us", "us", "us", "", "", "", "us", "us", "");
  for (int i = 0; i < repeats; ++i) {
    for (const bool storm : {false, true}) {
      options.storm = storm;
      const test::StormResult r = test::run_storm(options);
      if (!r.error.empty()) {
        std::fprintf(stderr, "storm_bench: %s\n%s\n", r.error.c_str(), r.outputs.c_str());
        return 1;
      }
      print_row(storm ? "storm" : "quiet", r);
    }
  }
  return 0;
}
