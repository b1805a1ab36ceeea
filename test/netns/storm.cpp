#include "storm.h"

#include <algorithm>
#include <csignal>
#include <initializer_list>
#include <sstream>

#include "netns_network.h"
#include "netns_nodes.h"

namespace teleop::test {
namespace {

constexpr int kRobotHost = 0;
constexpr int kOtherHost = 1;

YAML::Node transport_on(const NetnsNetwork& network, int host) {
  YAML::Node t;
  t["domain_id"] = 0;  // --domain decides
  t["udpv4"] = true;
  t["interface_whitelist"].push_back(network.address(host));
  return t;
}

int count_lines_with(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

void start_storm(NetnsNodes& nodes, const StormOptions& options) {
  const std::string domain = std::to_string(nodes.domain());
  const std::string seconds = std::to_string(options.seconds);
  for (int i = 0; i < options.readers; ++i) {
    const char* topic = i % 2 == 0 ? "teleop/follower/joint_state" : "teleop/follower/wrench";
    nodes.start_program("reader_" + std::to_string(i), kRobotHost,
                        {bin("teleop"), "topic", "hz", topic, "--domain", domain, "--duration", seconds});
  }
  nodes.start_program("churn", kOtherHost,
                      {bin("teleop_discovery_churn"), "--domain", domain, "--participants",
                       std::to_string(options.participants), "--duration", seconds});
}

// Fast DDS 2.9 (Debian builds it with assertions) aborts a process now and then when remote
// participants leave while their lease timer runs: a race between removal and lease check
bool aborted_by_fast_dds_removal_race(RunningProcess& p) {
  return p.output().find("PDP::check_remote_participant_liveliness") != std::string::npos;
}

// whether a storm program ended as it may: `clean` exit statuses, or aborted by Fast DDS's race
// (counted in `aborted`)
bool storm_program_ended(NetnsNodes& nodes, const std::string& name, std::initializer_list<int> clean, int& aborted) {
  const auto status = nodes.wait_exit(name, std::chrono::seconds(60));
  if (!status) return false;
  if (std::find(clean.begin(), clean.end(), *status) != clean.end()) return true;
  if (!aborted_by_fast_dds_removal_race(nodes.process(name))) return false;
  ++aborted;
  return true;
}

// the storm's programs end by themselves; the nodes are stopped together
std::string stop_all(NetnsNodes& nodes, const StormOptions& options, int& aborted) {
  if (options.storm) {
    // a reader that found no writer within its 2 s (a starved host discovers slowly) ends with 1:
    // it added to the storm all the same, and describe() counts the readers that received
    for (int i = 0; i < options.readers; ++i) {
      const std::string name = "reader_" + std::to_string(i);
      if (!storm_program_ended(nodes, name, {0, 1}, aborted)) return name + " did not end cleanly";
    }
    if (!storm_program_ended(nodes, "churn", {0}, aborted)) return "the churn did not end cleanly";
  }
  for (const char* node : {"leader", "follower"}) nodes.process(node).process().signal(SIGTERM);
  for (const char* node : {"leader", "follower"}) {
    if (nodes.wait_exit(node, std::chrono::seconds(30)) != 0) return std::string(node) + " did not exit cleanly";
  }
  return {};
}

}  // namespace

StormResult run_storm(const StormOptions& options) {
  StormResult result;
  NetnsNetwork network(2);
  NetnsNodes nodes(network);
  const double backstop_s = options.seconds + 60;
  const ConfigEdit realtime = [&](YAML::Node& root) { root["node"]["realtime"] = options.realtime; };
  nodes.start("follower", kRobotHost, transport_on(network, kRobotHost), backstop_s, realtime);
  nodes.start("leader", kRobotHost, transport_on(network, kRobotHost), backstop_s, realtime);
  if (!nodes.process("follower").wait_for_output("follows 'leader'", std::chrono::seconds(30))) {
    result.error = "the follower never followed the leader";
  } else {
    if (options.storm) start_storm(nodes, options);
    nodes.run_for(std::chrono::milliseconds(static_cast<int64_t>(options.seconds * 1000)));
  }
  const std::string stopped = stop_all(nodes, options, result.storm_processes_aborted);
  if (result.error.empty()) result.error = stopped;
  result.outputs = nodes.outputs();
  if (!result.error.empty()) return result;
  result.follower = nodes.report("follower");
  result.leader = nodes.report("leader");
  if (options.storm) {
    result.churn_rounds = count_lines_with(nodes.process("churn").output(), "participants up");
    for (int i = 0; i < options.readers; ++i) {
      result.readers_reporting += nodes.process("reader_" + std::to_string(i)).output().find(": rate ") != std::string::npos;
    }
  }
  return result;
}

std::string describe(const StormResult& r) {
  std::ostringstream out;
  const auto& f = r.follower;
  out << "follower: " << f.cycles << " cycles, lateness p50 " << f.lateness_p50_ns * 1e-3 << " us p99 "
      << f.lateness_p99_ns * 1e-3 << " us max " << f.lateness_max_ns * 1e-3 << " us, " << f.skipped << " skipped\n";
  for (const auto& [name, value] : f.counters) {
    if (name == "watchdog_trips" || name == "stall_holds" || name == "liveliness_trips") out << "  " << name << " " << value << "\n";
  }
  for (const auto& p : f.published) {
    out << "  wrote " << p.topic << ": " << p.sent << " sent, " << p.failed << " failed, write p99 "
        << p.write_p99_ns * 1e-3 << " us max " << p.write_max_ns * 1e-3 << " us\n";
  }
  out << "  churn rounds " << r.churn_rounds << ", readers receiving " << r.readers_reporting
      << ", storm processes aborted by Fast DDS's removal race " << r.storm_processes_aborted;
  return out.str();
}

}  // namespace teleop::test
