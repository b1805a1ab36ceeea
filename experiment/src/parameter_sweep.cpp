#include "parameter_sweep.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace teleop::experiment {
namespace {

constexpr const char* kOutcomeColumns =
    "contact_steps,peak_force_n,mean_force_n,final_error_m,wall_time_s,rt_factor,mujoco_warnings,error";

// a worker: variants worker, worker + jobs, ... into `path`, one "index;row" line each
void work(const SweepConfig& config, const std::vector<std::vector<double>>& grid, int worker, const std::string& path) {
  std::ofstream out(path);
  for (size_t i = static_cast<size_t>(worker); i < grid.size(); i += static_cast<size_t>(config.jobs)) {
    out << i << ';' << outcome_row(run_press_variant(config, grid[i])) << '\n';
    out.flush();
  }
}

std::vector<std::string> collect(const std::string& path, size_t variants) {
  std::vector<std::string> rows(variants);
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const size_t sep = line.find(';');
    const size_t index = std::stoul(line.substr(0, sep));
    if (index < variants) rows[index] = line.substr(sep + 1);
  }
  return rows;
}

}  // namespace

std::string outcome_row(const VariantOutcome& o) {
  std::ostringstream r;
  r.precision(10);
  for (double v : o.values) r << v << ',';
  r << o.contact_steps << ',' << o.peak_force_n << ',' << o.mean_force_n << ',' << o.final_error_m << ','
    << o.wall_time_s << ',' << o.rt_factor << ',' << o.mujoco_warnings << ",\"" << o.error << '"';
  return r.str();
}

std::string run_sweep(const SweepConfig& config) {
  const auto grid = sweep_grid(config.parameters);
  const std::string dir = (std::filesystem::temp_directory_path() / ("teleop_sweep_" + std::to_string(getpid()))).string();
  std::filesystem::create_directories(dir);
  std::vector<pid_t> workers;
  for (int w = 0; w < config.jobs; ++w) {
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("cannot start a sweep worker (fork failed)");
    if (pid == 0) {
      work(config, grid, w, dir + "/" + std::to_string(w));
      _exit(0);
    }
    workers.push_back(pid);
  }
  for (pid_t pid : workers) waitpid(pid, nullptr, 0);

  std::vector<std::string> rows(grid.size());
  for (int w = 0; w < config.jobs; ++w) {
    const auto part = collect(dir + "/" + std::to_string(w), grid.size());
    for (size_t i = 0; i < grid.size(); ++i) {
      if (!part[i].empty()) rows[i] = part[i];
    }
  }
  std::filesystem::remove_all(dir);

  std::ostringstream csv;
  for (const SweepParameter& p : config.parameters) csv << p.name << ',';
  csv << kOutcomeColumns << '\n';
  for (size_t i = 0; i < grid.size(); ++i) {
    if (rows[i].empty()) {
      VariantOutcome died;
      died.values = grid[i];
      died.error = "the worker died";
      rows[i] = outcome_row(died);
    }
    csv << rows[i] << '\n';
  }
  return csv.str();
}

}  // namespace teleop::experiment
