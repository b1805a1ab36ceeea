#include "teleop/experiment/plots.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "teleop/common/data_paths.h"

extern char** environ;

namespace teleop::experiment {
namespace fs = std::filesystem;
namespace {

constexpr const char* kInstallHint = "apt-get install python3-matplotlib (or scripts/setup.sh)";

// Runs `argv` (argv[0] looked up on PATH) and waits for it; its output goes to ours, or nowhere
// when `quiet`. Returns its exit status; -1 when it could not start or was killed.
int run_command(const std::vector<std::string>& argv, bool quiet) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  // what we printed comes before what the child prints
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string package_dir() {
  const std::string installed = "teleop_plot/__main__.py";
  const std::string in_source = "scripts/teleop_plot/__main__.py";
  const fs::path main_py = find_data(installed, in_source);
  if (!main_py.empty()) return main_py.parent_path().string();
  throw PlotError("the plotting package (teleop_plot/__main__.py) is in none of " +
                  data_candidates_text(installed, in_source, DataRoots::current()) +
                  " (install teleop, or build it from its source tree)");
}

std::string python_with_matplotlib() {
  const char* chosen = std::getenv("TELEOP_PYTHON");
  const std::vector<std::string> candidates =
      chosen != nullptr ? std::vector<std::string>{chosen} : std::vector<std::string>{"python3", "/usr/bin/python3"};
  std::string tried;
  for (const std::string& python : candidates) {
    if (run_command({python, "-c", "import matplotlib"}, true) == 0) return python;
    tried += (tried.empty() ? "" : ", ") + python;
  }
  throw PlotError("no python3 with matplotlib (tried " + tried + "): " + kInstallHint);
}

// a number as the package reads it back: shortest round trip
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

bool is_trace(const fs::path& file) {
  std::ifstream in(file);
  std::string header;
  return std::getline(in, header) && header.rfind("t_s,", 0) == 0;
}

// runs the package with `args`; its own messages say what it wrote, skipped or could not read
void run_package(const PlotTool& tool, std::vector<std::string> args, const std::string& what) {
  // -B: no __pycache__ written into the package (a source tree, or a read-only install)
  args.insert(args.begin(), {tool.python, "-B", tool.package_dir});
  const int status = run_command(args, false);
  if (status == 3) throw PlotError(tool.python + " has no matplotlib: " + kInstallHint);
  if (status != 0) {
    throw PlotError("the figures of " + what + " failed (" + tool.package_dir + " exit status " +
                    std::to_string(status) + ", its message above)");
  }
}

}  // namespace

PlotTool find_plot_tool() {
  PlotTool tool;
  tool.package_dir = package_dir();
  tool.python = python_with_matplotlib();
  return tool;
}

std::vector<std::string> run_traces(const std::string& run_dir) {
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) throw PlotError(run_dir + ": no such directory");
  std::vector<std::string> traces;
  for (const auto& entry : fs::directory_iterator(run_dir, ec)) {
    if (entry.path().extension() == ".csv" && is_trace(entry.path())) traces.push_back(entry.path().string());
  }
  std::sort(traces.begin(), traces.end());
  if (traces.empty()) {
    throw PlotError(run_dir +
                    ": no trace in this directory (expected <node>.csv files with a t_s column, as `teleop launch "
                    "--trace-dir` writes them; an experiment keeps each run's in <report dir>/<run>/<profile>/)");
  }
  return traces;
}

void plot_run(const PlotTool& tool, const std::string& run_dir, const std::string& out_dir, const RunMarks& marks) {
  run_traces(run_dir);
  std::vector<std::string> args{"run", run_dir, out_dir};
  if (!marks.leader.empty()) {
    args.insert(args.end(), {"--leader", marks.leader});
    for (const auto& [label, window] : marks.windows) {
      args.insert(args.end(), {"--window", label + "=" + number_text(window.first) + "," + number_text(window.second)});
    }
  }
  run_package(tool, args, run_dir);
}

void plot_recording_csv(const PlotTool& tool, const std::string& csv_dir, const std::string& out_dir) {
  run_package(tool, {"recording", csv_dir, out_dir}, csv_dir);
}

void plot_results(const PlotTool& tool, const std::string& csv_path,
                  const std::vector<std::pair<std::string, double>>& limits) {
  std::vector<std::string> args{"results", csv_path};
  for (const auto& [metric, value] : limits) args.insert(args.end(), {"--limit", metric + "=" + number_text(value)});
  run_package(tool, args, csv_path);
}

void plot_hand_study(const PlotTool& tool, const std::string& trace_csv, const std::string& out_dir) {
  run_package(tool, {"hand", trace_csv, out_dir}, trace_csv);
}

void plot_fidelity_study(const PlotTool& tool, const std::string& trace_csv, const std::string& segments_csv,
                         const std::string& out_dir) {
  run_package(tool, {"fidelity", trace_csv, segments_csv, out_dir}, trace_csv);
}

void plot_parti_study(const PlotTool& tool, const std::string& kind, const std::string& trace_csv,
                      const std::string& out_dir) {
  run_package(tool, {"parti", kind, trace_csv, out_dir}, trace_csv);
}

void plot_wiping_study(const PlotTool& tool, const std::string& wipes_csv, const std::string& trace_csv,
                       const std::string& out_dir) {
  run_package(tool, {"wiping", wipes_csv, trace_csv, out_dir}, wipes_csv);
}

}  // namespace teleop::experiment
