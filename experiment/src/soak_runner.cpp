#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <thread>

#include "report_files.h"
#include "soak_analysis.h"
#include "teleop/common/clock.h"
#include "teleop/experiment/soak.h"
#include "teleop/launcher/child_process.h"
#include "teleop/launcher/launcher.h"
#include "teleop/launcher/scenario.h"
#include "teleop/runtime/shutdown_signal.h"

namespace teleop::experiment {
namespace {

namespace fs = std::filesystem;

double now_s() { return static_cast<double>(monotonic_now_ns()) * 1e-9; }

// The soaked nodes: one running process per node at a time, each with its own trace (streamed, so
// that a SIGKILL leaves it behind), report and log file.
class SoakedNodes {
 public:
  SoakedNodes(const launcher::Scenario& scenario, const launcher::LaunchOptions& options, std::string dir)
      : scenario_(scenario), options_(options), dir_(std::move(dir)) {}
  ~SoakedNodes() { stop_all(); }

  void start(const launcher::NodeLaunch& spec) {
    const int incarnation = next_incarnation_[spec.name]++;
    const std::string base = (fs::path(dir_) / (spec.name + "_" + std::to_string(incarnation))).string();
    launcher::LaunchOptions options = options_;
    // each process draws its own losses, repeatably
    if (options.seed) *options.seed += static_cast<uint64_t>(incarnation);
    std::vector<std::string> argv = launcher::node_argv(scenario_, spec, options, base + ".yaml", base + ".csv");
    argv.push_back("--trace-stream");
    processes_.push_back({spec.name, incarnation, base + ".csv", base + ".yaml"});
    running_[spec.name] = {std::make_unique<launcher::ChildProcess>(launcher::ChildProcess::spawn(argv)),
                           std::make_unique<std::ofstream>(base + ".log")};
  }

  /// SIGKILL and reap: the node is gone when this returns.
  void kill(const std::string& node) {
    Running& r = running_.at(node);
    r.process->signal(SIGKILL);
    while (!r.process->wait_for(100)) forward(r);
    forward(r);
    running_.erase(node);
  }

  /// Keeps the children's pipes drained (into their logs) for `seconds`.
  void pump(double seconds) {
    const double until = now_s() + seconds;
    do {
      for (auto& [name, r] : running_) forward(r);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    } while (now_s() < until && !runtime::shutdown_requested());
  }

  /// SIGTERM to every node; SIGKILL to what has not ended after 10 s.
  void stop_all() {
    for (auto& [name, r] : running_) r.process->signal(SIGTERM);
    for (auto& [name, r] : running_) {
      for (int i = 0; i < 100 && !r.process->wait_for(100); ++i) forward(r);
      if (!r.process->try_wait()) {
        r.process->signal(SIGKILL);
        ++failures_;
      }
      forward(r);
    }
    running_.clear();
  }

  const std::vector<SoakProcess>& processes() const { return processes_; }
  int failures() const { return failures_; }

 private:
  struct Running {
    std::unique_ptr<launcher::ChildProcess> process;
    std::unique_ptr<std::ofstream> log;
  };
  static void forward(Running& r) {
    r.process->read_output([&](std::string_view line) { *r.log << line << '\n'; });
  }

  const launcher::Scenario& scenario_;
  launcher::LaunchOptions options_;
  std::string dir_;
  std::map<std::string, int> next_incarnation_;
  std::map<std::string, Running> running_;
  std::vector<SoakProcess> processes_;
  int failures_ = 0;
};

const launcher::NodeLaunch& node_of(const launcher::Scenario& scenario, const std::string& name) {
  for (const auto& n : scenario.nodes) {
    if (n.name == name) return n;
  }
  throw std::runtime_error("soak: no node " + name + " in the scenario");
}

// each node of `watch` `kills` times, in a seeded random order
std::vector<std::string> victims(const SoakConfig& config, int kills, std::mt19937_64& rng) {
  std::vector<std::string> out;
  for (const auto& [node, watchers] : config.watch) out.insert(out.end(), static_cast<size_t>(kills), node);
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

}  // namespace

SoakResult run_soak(const SoakConfig& config, const SoakOptions& options) {
  const launcher::Scenario scenario = launcher::load_scenario(config.scenario_path);
  const uint64_t seed = options.seed.value_or(config.seed);
  std::mt19937_64 rng(seed);
  const std::vector<std::string> order = victims(config, options.kills_per_node.value_or(config.kills_per_node), rng);

  launcher::LaunchOptions launch;
  launch.domain_id = options.domain_id;
  launch.network = config.network;
  launch.seed = seed;
  launch.bin_dir = options.bin_dir;
  launch.trace_seconds = 10.0;  // the ring only bridges the writer's periods: the file gets every row

  SoakResult result;
  result.report_dir = make_report_dir(options.report_dir, "teleop-soak-");
  std::printf("[soak    ] %s: %zu kills, seed %llu, network %s, into %s\n", config.name.c_str(), order.size(),
              static_cast<unsigned long long>(seed), config.network.empty() ? "none" : config.network.c_str(),
              result.report_dir.c_str());
  {
    SoakedNodes nodes(scenario, launch, result.report_dir);
    for (const auto& spec : scenario.nodes) nodes.start(spec);
    nodes.pump(config.settle_s);
    std::uniform_real_distribution<double> up(config.up_min_s, config.up_max_s);
    std::uniform_real_distribution<double> down(config.down_min_s, config.down_max_s);
    for (const std::string& victim : order) {
      if (runtime::shutdown_requested()) break;
      nodes.pump(up(rng));
      SoakEvent event;
      event.node = victim;
      event.incarnation = static_cast<int>(std::count_if(result.events.begin(), result.events.end(),
                                                         [&](const SoakEvent& e) { return e.node == victim; }));
      event.killed_s = now_s();
      nodes.kill(victim);
      nodes.pump(down(rng));
      event.restarted_s = now_s();
      nodes.start(node_of(scenario, victim));
      result.events.push_back(event);
      std::printf("[soak    ] %zu/%zu: %s killed and started again\n", result.events.size(), order.size(), victim.c_str());
    }
    nodes.pump(config.end_s);
    nodes.stop_all();
    result.failures += nodes.failures();
    analyse_soak(config, nodes.processes(), result);
  }
  result.csv_path = (fs::path(result.report_dir) / (config.name + ".csv")).string();
  std::ofstream(result.csv_path) << soak_csv(result);
  return result;
}

}  // namespace teleop::experiment
