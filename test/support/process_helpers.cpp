#include "process_helpers.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace teleop::test {
namespace fs = std::filesystem;

std::string bin(const std::string& name) { return std::string(TELEOP_BIN_DIR) + "/" + name; }

std::string source(const std::string& relative) { return std::string(TELEOP_SOURCE_DIR) + "/" + relative; }

int unique_domain() {
  // ctest runs each test in its own process: the pid spreads them over domains 100..199
  return 100 + static_cast<int>(getpid() % 100);
}

transport::ParticipantConfig bus_participant(int domain, const std::string& name) {
  transport::ParticipantConfig c;
  c.domain_id = domain;
  c.name = name;
  c.udpv4 = true;
  c.shm = false;
  return c;
}

std::string make_temp_dir() {
  std::string pattern = (fs::temp_directory_path() / "teleop-test-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<std::string> ProcessSite::args(const std::string& node, const std::string& config,
                                           const std::string& tag) const {
  return {bin("teleop_" + node),
          "--config",
          config,
          "--domain",
          std::to_string(domain),
          "--report",
          report_path(tag),
          "--trace",
          trace_path(tag),
          "--trace-seconds",
          "60"};
}

ProcessResult run_process(const std::vector<std::string>& argv, std::chrono::seconds timeout) {
  RunningProcess p(argv);
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!p.process().try_wait() && std::chrono::steady_clock::now() < until) {
    p.run_for(std::chrono::milliseconds(10));
  }
  ProcessResult result;
  result.exit_status = p.process().try_wait();
  p.run_for(std::chrono::milliseconds(10));
  result.output = p.output();
  return result;
}

RunningProcess::RunningProcess(const std::vector<std::string>& argv) : process_(launcher::ChildProcess::spawn(argv)) {}

void RunningProcess::collect() {
  process_.read_output([&](std::string_view line) {
    output_.append(line);
    output_.push_back('\n');
  });
}

void RunningProcess::run_for(std::chrono::milliseconds duration) {
  const auto until = std::chrono::steady_clock::now() + duration;
  do {
    collect();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (std::chrono::steady_clock::now() < until);
  collect();
}

bool RunningProcess::wait_for_output(const std::string& text, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (output_.find(text) == std::string::npos) {
    if (std::chrono::steady_clock::now() >= until || process_.try_wait()) return false;
    run_for(std::chrono::milliseconds(10));
  }
  return true;
}

std::optional<int> RunningProcess::stop(int sig, std::chrono::seconds timeout) {
  process_.signal(sig);
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!process_.try_wait() && std::chrono::steady_clock::now() < until) run_for(std::chrono::milliseconds(10));
  run_for(std::chrono::milliseconds(10));
  return process_.try_wait();
}

std::string config_copy(const std::string& dir, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string text = read_file(source("config/nodes/" + name));
  for (size_t at = text.find("../models/"); at != std::string::npos; at = text.find("../models/", at)) {
    text.replace(at, 10, source("config/models/"));
  }
  for (const auto& [from, to] : edits) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error(name + " changed: no '" + from + "'; update this test");
    text.replace(at, from.size(), to);
  }
  const std::string path = dir + "/" + name;
  write_file(path, text);
  return path;
}

}  // namespace teleop::test
