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

std::string churn_name(int run) { return "churn_" + std::to_string(run); }

void start_churn(NetnsNodes& nodes, const StormOptions& options, int run, double seconds) {
  nodes.start_program(churn_name(run), kOtherHost,
                      {bin("teleop_discovery_churn"), "--domain", std::to_string(nodes.domain()), "--participants",
                       std::to_string(options.participants), "--duration", std::to_string(seconds)});
}

void start_readers(NetnsNodes& nodes, const StormOptions& options) {
  const std::string domain = std::to_string(nodes.domain());
  const std::string seconds = std::to_string(options.seconds);
  for (int i = 0; i < options.readers; ++i) {
    const char* topic = i % 2 == 0 ? "teleop/follower/joint_state" : "teleop/follower/wrench";
    nodes.start_program("reader_" + std::to_string(i), kRobotHost,
                        {bin("teleop"), "topic", "hz", topic, "--domain", domain, "--duration", seconds});
  }
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

// lines with `what` in the output of all churn runs
int churn_lines_with(NetnsNodes& nodes, int churn_runs, const std::string& what) {
  int lines = 0;
  for (int run = 0; run < churn_runs; ++run) lines += count_lines_with(nodes.process(churn_name(run)).output(), what);
  return lines;
}

int churn_rounds(NetnsNodes& nodes, int churn_runs) { return churn_lines_with(nodes, churn_runs, "participants up"); }

// The churn for options.seconds, until its last run ended. A run that Fast DDS aborted in its
// removal race (readers leaving while thirty participants are created can set it off before the
// first round) is started again for the time left, or once more if no round completed yet: the
// storm goes on, and every abort is counted. A run still in its last round kGraceS after the storm
// is killed (counted): on two cores the follower's middleware threads at SCHED_FIFO, busy with the
// storm's discovery, can starve the churn's thirty deletions for a minute, and the churn's clean
// exit is not what the test is about. Returns why the churn did not end as it may ("" when it
// did); `runs` is how many churn processes ran.
std::string churn_for(NetnsNodes& nodes, const StormOptions& options, int& runs, StormResult& result) {
  constexpr int kMaxRuns = 5;
  constexpr int kGraceS = 20;
  const auto start = std::chrono::steady_clock::now();
  const auto left_s = [&] {
    return options.seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  start_churn(nodes, options, runs++, options.seconds);
  for (;;) {
    const std::string name = churn_name(runs - 1);
    const auto status = nodes.wait_exit(name, std::chrono::seconds(std::max(0, static_cast<int>(left_s())) + kGraceS));
    if (!status) {
      nodes.process(name).process().signal(SIGKILL);
      result.churn_killed_after_the_storm = true;
      return nodes.wait_exit(name, std::chrono::seconds(10)) ? "" : name + " did not end when killed";
    }
    if (*status == 0) return {};
    if (!aborted_by_fast_dds_removal_race(nodes.process(name))) return name + " failed";
    ++result.storm_processes_aborted;
    if (runs == kMaxRuns || (left_s() < 2 && churn_lines_with(nodes, runs, "joined churn_") > 0)) return {};
    start_churn(nodes, options, runs++, std::max(left_s(), 1.0));
  }
}

// the readers end by themselves; the nodes are stopped together
std::string stop_all(NetnsNodes& nodes, const StormOptions& options, bool storm, int& aborted) {
  if (storm) {
    // a reader that found no writer within its 2 s (a starved host discovers slowly) ends with 1:
    // it added to the storm all the same, and describe() counts the readers that received
    for (int i = 0; i < options.readers; ++i) {
      const std::string name = "reader_" + std::to_string(i);
      if (!storm_program_ended(nodes, name, {0, 1}, aborted)) return name + " did not end cleanly";
    }
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
  int churn_runs = 0;
  std::string churn_error;
  if (!nodes.process("follower").wait_for_output("follows 'leader'", std::chrono::seconds(30))) {
    result.error = "the follower never followed the leader";
  } else if (options.storm) {
    start_readers(nodes, options);
    churn_error = churn_for(nodes, options, churn_runs, result);
  } else {
    nodes.run_for(std::chrono::milliseconds(static_cast<int64_t>(options.seconds * 1000)));
  }
  const std::string stopped = stop_all(nodes, options, churn_runs > 0, result.storm_processes_aborted);
  for (const std::string& error : {churn_error, stopped}) {
    if (result.error.empty()) result.error = error;
  }
  result.outputs = nodes.outputs();
  if (!result.error.empty()) return result;
  result.follower = nodes.report("follower");
  result.leader = nodes.report("leader");
  if (options.storm) {
    result.churn_rounds = churn_rounds(nodes, churn_runs);
    result.participants_joined = churn_lines_with(nodes, churn_runs, "joined churn_");
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
  out << "  churn rounds " << r.churn_rounds << " (" << r.participants_joined << " participants joined), readers receiving " << r.readers_reporting
      << ", storm processes aborted by Fast DDS's removal race " << r.storm_processes_aborted
      << (r.churn_killed_after_the_storm ? ", the churn killed in its last round after the storm" : "");
  return out.str();
}

}  // namespace teleop::test
