#include "netns_network.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "process_helpers.h"

namespace teleop::test {
namespace {

// every name starts with this, then the pid of the creating process and a counter letter
constexpr const char* kPrefix = "tn";

ProcessResult ip(const std::vector<std::string>& args) {
  std::vector<std::string> argv{system_tool("ip")};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_process(argv, std::chrono::seconds(10));
}

void must(const std::vector<std::string>& args) {
  const ProcessResult r = ip(args);
  if (r.exit_status != 0) {
    std::string command = "ip";
    for (const auto& a : args) command += " " + a;
    throw std::runtime_error("netns: '" + command + "' failed: " + r.output);
  }
}

bool process_alive(pid_t pid) { return kill(pid, 0) == 0 || errno == EPERM; }

// names of namespaces and bridges left behind by runs whose process is gone
void remove_leftovers() {
  const std::regex name(std::string(kPrefix) + "([0-9]+)[a-z](-h[0-9]+|br)");
  std::stringstream listing(ip({"netns", "list"}).output + "\n" + ip({"-o", "link", "show", "type", "bridge"}).output);
  std::string word;
  while (listing >> word) {
    if (!word.empty() && word.back() == ':') word.pop_back();
    std::smatch m;
    if (!std::regex_match(word, m, name) || process_alive(static_cast<pid_t>(std::stol(m[1].str())))) continue;
    if (m[2].str() == "br") {
      ip({"link", "del", word});
    } else {
      ip({"netns", "del", word});
    }
  }
}

}  // namespace

std::string system_tool(const std::string& name) {
  for (const char* dir : {"/usr/sbin/", "/usr/bin/", "/sbin/", "/bin/"}) {
    const std::string path = dir + name;
    if (access(path.c_str(), X_OK) == 0) return path;
  }
  throw std::runtime_error("netns: '" + name + "' is not installed (scripts/setup.sh installs it)");
}

std::string netns_unavailable_reason() {
  if (geteuid() != 0) {
    return "network namespace tests need root (they create namespaces, veth pairs and a bridge); run them as root "
           "or deselect them with ctest -LE netns";
  }
  try {
    NetnsNetwork probe(1);
  } catch (const std::exception& e) {
    return std::string("network namespaces do not work here: ") + e.what();
  }
  return {};
}

NetnsNetwork::NetnsNetwork(int hosts) {
  static std::atomic<int> counter{0};
  tag_ = kPrefix + std::to_string(getpid()) + static_cast<char>('a' + counter++ % 26);
  remove_leftovers();
  try {
    must({"link", "add", bridge(), "type", "bridge", "mcast_snooping", "0"});
    must({"link", "set", bridge(), "up"});
    for (int h = 0; h < hosts; ++h) add_host(h);
  } catch (...) {
    remove_all();
    throw;
  }
}

NetnsNetwork::~NetnsNetwork() { remove_all(); }

std::string NetnsNetwork::host_namespace(int host) const { return tag_ + "-h" + std::to_string(host); }

std::string NetnsNetwork::address(int host) const { return "10.200.0." + std::to_string(host + 1); }

std::vector<std::string> NetnsNetwork::on_host(int host, const std::vector<std::string>& argv) const {
  std::vector<std::string> out{system_tool("ip"), "netns", "exec", host_namespace(host)};
  out.insert(out.end(), argv.begin(), argv.end());
  return out;
}

void NetnsNetwork::add_host(int host) {
  const std::string ns = host_namespace(host);
  must({"netns", "add", ns});
  hosts_ = host + 1;  // from here on the namespace is ours to delete
  must({"link", "add", port(host), "type", "veth", "peer", "name", "eth0", "netns", ns});
  must({"link", "set", port(host), "master", bridge(), "up"});
  must({"-n", ns, "link", "set", "lo", "up"});
  must({"-n", ns, "addr", "add", address(host) + "/24", "dev", "eth0"});
  must({"-n", ns, "link", "set", "eth0", "up"});
  must({"-n", ns, "route", "add", "default", "dev", "eth0"});
}

void NetnsNetwork::set_link_up(int host, bool up) { must({"link", "set", port(host), up ? "up" : "down"}); }

void NetnsNetwork::block_multicast() {
  for (int h = 0; h < hosts_; ++h) {
    const ProcessResult r = run_process({system_tool("bridge"), "link", "set", "dev", port(h), "mcast_flood", "off"},
                                        std::chrono::seconds(10));
    if (r.exit_status != 0) throw std::runtime_error("netns: cannot block multicast on " + port(h) + ": " + r.output);
  }
}

void NetnsNetwork::remove_all() noexcept {
  try {
    // a namespace takes its end of the veth pair along, and with it the bridge port
    for (int h = 0; h < hosts_; ++h) ip({"netns", "del", host_namespace(h)});
    ip({"link", "del", bridge()});
  } catch (...) {
    // best effort: the next network removes what is left (its pid is gone by then)
  }
}

}  // namespace teleop::test
