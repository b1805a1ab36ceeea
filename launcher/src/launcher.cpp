#include "teleop/launcher/launcher.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/launcher/child_process.h"
#include "teleop/launcher/status_monitor.h"
#include "teleop/runtime/shutdown_signal.h"

namespace teleop::launcher {
namespace fs = std::filesystem;
namespace {

struct RunningNode {
  const NodeLaunch* spec;
  ChildProcess process;
  std::string report_path;
};

bool is_executable(const fs::path& p) { return fs::is_regular_file(p) && access(p.c_str(), X_OK) == 0; }

std::string make_report_dir(const std::string& requested) {
  if (!requested.empty()) {
    fs::create_directories(requested);
    return requested;
  }
  std::string pattern = (fs::temp_directory_path() / "teleop-run-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a report directory in /tmp");
  return pattern;
}

void forward_output(RunningNode& node) {
  node.process.read_output([&](std::string_view line) {
    std::printf("[%-8s] %.*s\n", node.spec->name.c_str(), static_cast<int>(line.size()), line.data());
  });
  std::fflush(stdout);
}

// waits up to 50 ms for output from any node and forwards it, with the statuses on the bus
void pump_output(std::vector<RunningNode>& nodes, StatusMonitor& monitor) {
  std::vector<pollfd> fds;
  for (auto& n : nodes) {
    if (n.process.output_fd() >= 0) fds.push_back({n.process.output_fd(), POLLIN, 0});
  }
  if (fds.empty()) {
    usleep(50'000);
  } else {
    poll(fds.data(), fds.size(), 50);
  }
  for (auto& n : nodes) forward_output(n);
  monitor.poll();
}

// the peers whose links from `node` the network profile impairs: every one ("*"), or with sites
// the nodes at other sites
std::vector<std::string> impaired_peers(const Scenario& scenario, const NodeLaunch& node) {
  const bool sited = std::any_of(scenario.nodes.begin(), scenario.nodes.end(), [](const NodeLaunch& n) { return !n.site.empty(); });
  if (!sited) return {"*"};
  std::vector<std::string> peers;
  for (const NodeLaunch& other : scenario.nodes) {
    if (other.site != node.site) peers.push_back(other.name);
  }
  return peers;
}

std::vector<RunningNode> start_nodes(const Scenario& scenario, const LaunchOptions& options,
                                     const std::string& report_dir) {
  std::vector<RunningNode> nodes;
  for (const auto& spec : scenario.nodes) {
    const std::string report = (fs::path(report_dir) / (spec.name + ".yaml")).string();
    const std::string trace =
        options.trace_dir.empty() ? "" : (fs::path(options.trace_dir) / (spec.name + ".csv")).string();
    const std::vector<std::string> argv = node_argv(scenario, spec, options, report, trace);
    std::printf("[launch  ] starting %s: %s --config %s\n", spec.name.c_str(), argv[0].c_str(), spec.config.c_str());
    nodes.push_back({&spec, ChildProcess::spawn(argv), report});
  }
  return nodes;
}

// runs until the duration is over, a signal arrives, or a node exits; true if a node failed
bool supervise(std::vector<RunningNode>& nodes, StatusMonitor& monitor, double duration_s) {
  const int64_t end_ns = duration_s > 0 ? monotonic_now_ns() + static_cast<int64_t>(duration_s * 1e9) : INT64_MAX;
  while (!runtime::shutdown_requested() && monotonic_now_ns() < end_ns) {
    pump_output(nodes, monitor);
    for (auto& n : nodes) {
      if (auto status = n.process.try_wait()) {
        std::printf("[launch  ] %s exited early with status %d: stopping the others\n", n.spec->name.c_str(), *status);
        return true;
      }
    }
  }
  return false;
}

// SIGTERM to all, wait for them (forwarding their last words), SIGKILL what is left
bool stop_nodes(std::vector<RunningNode>& nodes, StatusMonitor& monitor, double stop_timeout_s) {
  for (auto& n : nodes) n.process.signal(SIGTERM);
  const int64_t deadline = monotonic_now_ns() + static_cast<int64_t>(stop_timeout_s * 1e9);
  auto all_exited = [&] {
    bool all = true;
    for (auto& n : nodes) all = n.process.try_wait().has_value() && all;
    return all;
  };
  while (!all_exited() && monotonic_now_ns() < deadline) pump_output(nodes, monitor);
  bool clean = true;
  for (auto& n : nodes) {
    if (!n.process.try_wait()) {
      std::printf("[launch  ] %s did not stop within %.1f s: killed\n", n.spec->name.c_str(), stop_timeout_s);
      n.process.signal(SIGKILL);
      n.process.wait_for(1000);
      clean = false;
    } else if (*n.process.exit_status() != 0) {
      std::printf("[launch  ] %s exited with status %d\n", n.spec->name.c_str(), *n.process.exit_status());
      clean = false;
    }
  }
  // drain whatever is left in the pipes
  for (int i = 0; i < 3; ++i) pump_output(nodes, monitor);
  return clean;
}

}  // namespace

std::vector<std::string> node_argv(const Scenario& scenario, const NodeLaunch& spec, const LaunchOptions& options,
                                   const std::string& report_path, const std::string& trace_path) {
  std::vector<std::string> argv{find_executable(spec.executable, options.bin_dir), "--config", spec.config, "--report",
                                report_path};
  if (options.domain_id) {
    argv.push_back("--domain");
    argv.push_back(std::to_string(*options.domain_id));
  }
  for (const std::string& peer : impaired_peers(scenario, spec)) {
    if (options.network.empty()) break;
    argv.push_back("--impair");
    argv.push_back(peer + "=" + options.network);
  }
  if (options.seed) {
    argv.push_back("--seed");
    argv.push_back(std::to_string(*options.seed));
  }
  for (const std::string& set : node_overrides(scenario, spec, options.sets)) {
    argv.push_back("--set");
    argv.push_back(set);
  }
  if (!trace_path.empty()) {
    argv.push_back("--trace");
    argv.push_back(trace_path);
    if (options.trace_seconds) {
      argv.push_back("--trace-seconds");
      argv.push_back(std::to_string(*options.trace_seconds));
    }
  }
  argv.insert(argv.end(), spec.args.begin(), spec.args.end());
  return argv;
}

std::vector<std::string> node_overrides(const Scenario& scenario, const NodeLaunch& node,
                                        const std::vector<std::string>& sets) {
  std::vector<std::string> out = node.sets;
  for (const std::string& set : sets) {
    const auto colon = set.find(':');
    const auto eq = set.find('=');
    if (colon == std::string::npos || colon == 0 || eq == std::string::npos || eq < colon) {
      throw ConfigError("--set " + set + ": expected NODE:KEY=VALUE, e.g. leader:node.rate_hz=500");
    }
    const std::string target = set.substr(0, colon);
    const bool known = std::any_of(scenario.nodes.begin(), scenario.nodes.end(),
                                   [&](const NodeLaunch& n) { return n.name == target; });
    if (!known) throw ConfigError("--set " + set + ": scenario " + scenario.name + " has no node '" + target + "'");
    if (target == node.name) out.push_back(set.substr(colon + 1));
  }
  return out;
}

std::string find_executable(const std::string& name, const std::string& bin_dir) {
  if (name.find('/') != std::string::npos) {
    if (is_executable(name)) return name;
    throw std::runtime_error("node executable " + name + " not found");
  }
  std::vector<fs::path> candidates;
  if (!bin_dir.empty()) candidates.push_back(fs::path(bin_dir) / name);
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(self.parent_path() / name);
  if (const char* path = std::getenv("PATH")) {
    std::string_view rest(path);
    while (!rest.empty()) {
      const auto colon = rest.find(':');
      candidates.push_back(fs::path(std::string(rest.substr(0, colon))) / name);
      rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
    }
  }
  for (const auto& c : candidates) {
    if (is_executable(c)) return c.string();
  }
  throw std::runtime_error("node executable " + name + " not found next to the launcher or on PATH");
}

LaunchResult launch(const Scenario& scenario, const LaunchOptions& options) {
  LaunchResult result;
  result.report_dir = make_report_dir(options.report_dir);
  const double duration_s = options.duration_s.value_or(scenario.duration_s);
  runtime::install_shutdown_handlers();
  // bad overrides fail here, before any node starts
  for (const auto& node : scenario.nodes) node_overrides(scenario, node, options.sets);
  if (!options.trace_dir.empty()) fs::create_directories(options.trace_dir);

  StatusMonitor monitor(scenario_domain(scenario.nodes.front().config, options.domain_id), [](const std::string& line) {
    std::printf("[status  ] %s\n", line.c_str());
  });
  std::vector<RunningNode> nodes = start_nodes(scenario, options, result.report_dir);
  std::printf("[launch  ] %zu nodes running for %s\n", nodes.size(),
              duration_s > 0 ? (std::to_string(duration_s) + " s").c_str() : "until Ctrl-C");
  const bool failed = supervise(nodes, monitor, duration_s);
  const bool clean = stop_nodes(nodes, monitor, scenario.stop_timeout_s);

  std::vector<runtime::NodeReport> reports;
  bool all_reported = true;
  for (const auto& n : nodes) {
    if (fs::exists(n.report_path)) {
      reports.push_back(runtime::read_report(n.report_path));
    } else {
      std::printf("[launch  ] %s wrote no report\n", n.spec->name.c_str());
      all_reported = false;
    }
  }
  result.summary = summarize(std::move(reports));
  result.summary.bus_status = monitor.nodes();
  result.exit_code = (!failed && clean && all_reported) ? 0 : 1;
  return result;
}

}  // namespace teleop::launcher
