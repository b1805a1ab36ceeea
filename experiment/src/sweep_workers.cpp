#include "sweep_workers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace teleop::experiment {
namespace {

// a worker: cells worker, worker + jobs, ... into `path`, one "index;line" line each, flushed
// after each so a crash later keeps what was done
void work(size_t cells, int jobs, int worker, const std::function<std::string(size_t)>& run_cell,
          const std::string& path) {
  std::ofstream out(path);
  for (size_t i = static_cast<size_t>(worker); i < cells; i += static_cast<size_t>(jobs)) {
    out << i << ';' << run_cell(i) << '\n';
    out.flush();
  }
}

void collect(const std::string& path, std::vector<std::string>& lines) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const size_t sep = line.find(';');
    if (sep == std::string::npos) continue;
    const size_t index = std::stoul(line.substr(0, sep));
    if (index < lines.size()) lines[index] = line.substr(sep + 1);
  }
}

}  // namespace

std::vector<std::string> run_in_workers(size_t cells, int jobs, const std::function<std::string(size_t)>& run_cell) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("teleop_sweep_" + std::to_string(getpid()))).string();
  std::filesystem::create_directories(dir);
  std::vector<pid_t> workers;
  for (int w = 0; w < jobs; ++w) {
    const pid_t pid = fork();
    if (pid < 0) {
      for (pid_t started : workers) waitpid(started, nullptr, 0);
      std::filesystem::remove_all(dir);
      throw std::runtime_error("cannot start a sweep worker (fork failed)");
    }
    if (pid == 0) {
      work(cells, jobs, w, run_cell, dir + "/" + std::to_string(w));
      _exit(0);
    }
    workers.push_back(pid);
  }
  for (pid_t pid : workers) waitpid(pid, nullptr, 0);
  std::vector<std::string> lines(cells);
  for (int w = 0; w < jobs; ++w) collect(dir + "/" + std::to_string(w), lines);
  std::filesystem::remove_all(dir);
  return lines;
}

}  // namespace teleop::experiment
