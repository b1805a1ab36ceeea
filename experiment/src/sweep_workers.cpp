#include "sweep_workers.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace teleop::experiment {
namespace {

// one line per cell: a newline in a cell's text (a multi-line MuJoCo error) would split it
std::string one_line(std::string text) {
  for (char& c : text) c = (c == '\n' || c == '\r') ? ' ' : c;
  return text;
}

// a worker: cells worker, worker + jobs, ... into `path`, one "index;line" line each, flushed
// after each so a crash later keeps what was done. False when the file cannot be written.
bool work(size_t cells, int jobs, int worker, const std::function<std::string(size_t)>& run_cell,
          const std::string& path) {
  std::ofstream out(path);
  for (size_t i = static_cast<size_t>(worker); out && i < cells; i += static_cast<size_t>(jobs)) {
    out << i << ';' << one_line(run_cell(i)) << '\n';
    out.flush();
  }
  return static_cast<bool>(out);
}

// the forked child: it never returns into the parent's stack (whose catch handlers and exit path
// are the parent's), and stops on Ctrl-C or SIGTERM like any process (the parent's handlers, copied
// by fork, only set a flag the child never reads)
[[noreturn]] void run_worker(size_t cells, int jobs, int worker, const std::function<std::string(size_t)>& run_cell,
                             const std::string& path) {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  int status = 2;
  try {
    status = work(cells, jobs, worker, run_cell, path) ? 0 : 3;
  } catch (...) {
    status = 2;
  }
  _exit(status);
}

// the lines a worker finished: a last line without its newline was cut by the worker's death
void collect(const std::string& path, std::vector<std::string>& lines) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && !in.eof()) {
    const size_t sep = line.find(';');
    if (sep == std::string::npos) continue;
    size_t index = 0;
    const auto [end, ec] = std::from_chars(line.data(), line.data() + sep, index);
    if (ec != std::errc() || end != line.data() + sep || index >= lines.size()) continue;
    lines[index] = line.substr(sep + 1);
  }
}

// waits for a worker through signals arriving in the parent (SIGINT handlers without SA_RESTART)
void wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

}  // namespace

std::vector<std::string> run_in_workers(size_t cells, int jobs, const std::function<std::string(size_t)>& run_cell) {
  if (jobs < 1) throw std::invalid_argument("a sweep needs at least one worker, not " + std::to_string(jobs));
  std::string dir = (std::filesystem::temp_directory_path() / "teleop-sweep-XXXXXX").string();
  if (mkdtemp(dir.data()) == nullptr) {
    throw std::runtime_error("cannot make the sweep's folder " + dir + ": " + std::strerror(errno));
  }
  std::vector<pid_t> workers;
  for (int w = 0; w < jobs; ++w) {
    const pid_t pid = fork();
    if (pid < 0) {
      for (pid_t started : workers) {
        kill(started, SIGTERM);
        wait_for(started);
      }
      std::filesystem::remove_all(dir);
      throw std::runtime_error("cannot start a sweep worker (fork failed)");
    }
    if (pid == 0) run_worker(cells, jobs, w, run_cell, dir + "/" + std::to_string(w));
    workers.push_back(pid);
  }
  for (pid_t pid : workers) wait_for(pid);
  std::vector<std::string> lines(cells);
  for (int w = 0; w < jobs; ++w) collect(dir + "/" + std::to_string(w), lines);
  std::filesystem::remove_all(dir);
  return lines;
}

}  // namespace teleop::experiment
