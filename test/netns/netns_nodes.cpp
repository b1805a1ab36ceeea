#include "netns_nodes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace teleop::test {
namespace fs = std::filesystem;

NetnsNodes::NetnsNodes(const NetnsNetwork& network)
    : network_(network), dir_(make_temp_dir()), domain_(unique_domain()) {
  // node configs name their MuJoCo model relative to themselves (../models/...)
  fs::create_directories(dir_ + "/nodes");
  fs::create_directory_symlink(source("config/models"), dir_ + "/models");
}

std::string NetnsNodes::write_config(const std::string& role, const std::string& name, const YAML::Node& transport,
                                     const ConfigEdit& edit) const {
  YAML::Node root = YAML::LoadFile(source("config/nodes/" + role + ".yaml"));
  root["node"]["name"] = name;
  root["transport"] = YAML::Clone(transport);
  if (edit) edit(root);
  YAML::Emitter out;
  out << root;
  const std::string path = dir_ + "/nodes/" + name + ".yaml";
  write_file(path, std::string(out.c_str()) + "\n");
  return path;
}

RunningProcess& NetnsNodes::start(const std::string& role, int host, const YAML::Node& transport, double duration_s,
                                  const ConfigEdit& edit, const std::string& name) {
  const std::string node = name.empty() ? role : name;
  const std::string config = write_config(role, node, transport, edit);
  return start_program(node, host,
                       {bin("teleop_" + role), "--config", config, "--domain", std::to_string(domain_), "--duration",
                        std::to_string(duration_s), "--report", report_path(node)});
}

RunningProcess& NetnsNodes::start_program(const std::string& name, int host, const std::vector<std::string>& argv) {
  if (processes_.count(name) != 0) throw std::logic_error("netns: process " + name + " started twice");
  auto process = std::make_unique<RunningProcess>(network_.on_host(host, argv));
  return *processes_.emplace(name, std::move(process)).first->second;
}

std::optional<int> NetnsNodes::wait_exit(const std::string& name, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  RunningProcess& p = process(name);
  while (!p.process().try_wait() && std::chrono::steady_clock::now() < until) run_for(std::chrono::milliseconds(20));
  run_for(std::chrono::milliseconds(10));
  return p.process().try_wait();
}

void NetnsNodes::run_for(std::chrono::milliseconds duration) {
  const auto until = std::chrono::steady_clock::now() + duration;
  do {
    for (auto& [name, p] : processes_) p->run_for(std::chrono::milliseconds(0));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  } while (std::chrono::steady_clock::now() < until);
}

std::string NetnsNodes::outputs() const {
  std::string all;
  for (const auto& [name, p] : processes_) all += "---- " + name + " ----\n" + p->output();
  return all;
}

const runtime::ReceivedTopic& received(const runtime::NodeReport& report, const std::string& topic) {
  for (const auto& t : report.received) {
    if (t.topic == topic) return t;
  }
  static const runtime::ReceivedTopic none;
  ADD_FAILURE() << report.name << " reports no received topic " << topic;
  return none;
}

double counter(const runtime::NodeReport& report, const std::string& name) {
  for (const auto& [n, v] : report.counters) {
    if (n == name) return v;
  }
  ADD_FAILURE() << report.name << " reports no counter " << name;
  return -1;
}

}  // namespace teleop::test
