// teleop_twin_sweep: runs a parameter sweep of the twin's simulation and writes the table (docs/twin.md).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <iostream>

#include "parameter_sweep.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/version.h"

int main(int argc, char** argv) {
  CLI::App app{"teleop twin sweep: one scenario over a grid of parameters, in parallel processes",
               "teleop_twin_sweep"};
  app.set_version_flag("--version", teleop::version_text());
  std::string config_path;
  std::string out_path;
  std::optional<int> jobs;
  app.add_option("-c,--config", config_path, "YAML sweep configuration: a file, or a name in config/sweeps")
      ->required();
  app.add_option("-o,--out", out_path, "write the table as CSV to this file (default: stdout)");
  app.add_option("-j,--jobs", jobs, "worker processes (overrides sweep.jobs)")->check(CLI::Range(1, 64));
  CLI11_PARSE(app, argc, argv);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  try {
    const teleop::ConfigNode root = teleop::ConfigNode::load_file(teleop::resolve_config("sweeps", config_path));
    teleop::experiment::SweepConfig config = teleop::experiment::parse_sweep_config(root);
    root.check_all_used();
    if (jobs) config.jobs = *jobs;
    const auto start = std::chrono::steady_clock::now();
    const std::string table = teleop::experiment::run_sweep(config);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (out_path.empty()) {
      std::cout << table;
    } else {
      std::ofstream(out_path) << table;
    }
    spdlog::info("sweep: {} variants in {} processes, {:.2f} s wall", teleop::experiment::sweep_grid(config.parameters).size(),
                 config.jobs, wall_s);
    return 0;
  } catch (const teleop::ConfigError& e) {
    spdlog::error("config error: {}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("sweep: {}", e.what());
    return 1;
  }
}
