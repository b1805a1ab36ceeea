// The facts read from files under a root: the kernel's flags, the governors, the time daemons,
// the input devices and the provisioning files (host_reader.h).
#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "teleop/doctor/host_reader.h"

namespace teleop::doctor {
namespace {

namespace fs = std::filesystem;

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// the number after `prefix` in a name like cpu12 or event3; -1 when it is not one
int numbered(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) return -1;
  const std::string digits = name.substr(prefix.size());
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) return -1;
  return std::stoi(digits);
}

// the entries of `dir` named prefix<N>, in the order of N
std::vector<fs::path> numbered_entries(const fs::path& dir, const std::string& prefix) {
  std::vector<std::pair<int, fs::path>> found;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const int n = numbered(e.path().filename().string(), prefix);
    if (n >= 0) found.emplace_back(n, e.path());
  }
  std::sort(found.begin(), found.end());
  std::vector<fs::path> paths;
  for (auto& [n, p] : found) paths.push_back(std::move(p));
  return paths;
}

bool exists_in(const std::string& root, std::initializer_list<const char*> candidates) {
  std::error_code ec;
  return std::any_of(candidates.begin(), candidates.end(),
                     [&](const char* c) { return fs::exists(fs::path(root) / c, ec); });
}

std::string group_of(const fs::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return {};
  const group* g = ::getgrgid(st.st_gid);
  return g == nullptr ? std::to_string(st.st_gid) : g->gr_name;
}

// the preemption model the kernel was booted with, "none voluntary (full) lazy" -> "full"
std::string chosen_preemption(const std::string& line) {
  const auto open = line.find('(');
  const auto close = line.find(')', open);
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

}  // namespace

KernelFacts read_kernel(const std::string& root) {
  KernelFacts k;
  utsname u{};
  if (::uname(&u) == 0) {
    k.release = u.release;
    k.version = u.version;
  }
  k.realtime_flag = first_line(fs::path(root) / "sys/kernel/realtime") == "1";
  k.preemption = chosen_preemption(first_line(fs::path(root) / "sys/kernel/debug/sched/preempt"));
  return k;
}

std::vector<std::string> read_governors(const std::string& root) {
  std::vector<std::string> governors;
  for (const fs::path& cpu : numbered_entries(fs::path(root) / "sys/devices/system/cpu", "cpu")) {
    const std::string g = first_line(cpu / "cpufreq/scaling_governor");
    if (!g.empty()) governors.push_back(g);
  }
  return governors;
}

std::vector<std::string> read_time_daemons(const std::string& root) {
  // comm is cut at 15 characters
  static const std::vector<std::pair<std::string, std::string>> kDaemons = {
      {"chronyd", "chronyd"}, {"ptp4l", "ptp4l"}, {"phc2sys", "phc2sys"},
      {"systemd-timesyn", "systemd-timesyncd"}, {"ntpd", "ntpd"}, {"openntpd", "openntpd"}};
  std::vector<std::string> running;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(root) / "proc", ec)) {
    if (numbered(e.path().filename().string(), "") < 0) continue;  // a process
    const std::string comm = first_line(e.path() / "comm");
    for (const auto& [as_comm, name] : kDaemons) {
      if (comm == as_comm && std::find(running.begin(), running.end(), name) == running.end()) running.push_back(name);
    }
  }
  std::sort(running.begin(), running.end());
  return running;
}

std::vector<InputDeviceFacts> read_input_devices(const std::string& root) {
  std::vector<InputDeviceFacts> devices;
  for (const fs::path& node : numbered_entries(fs::path(root) / "dev/input", "event")) {
    InputDeviceFacts d;
    d.path = node.string();
    d.name = first_line(fs::path(root) / "sys/class/input" / node.filename() / "device/name");
    d.group = group_of(node);
    d.readable = ::access(node.c_str(), R_OK) == 0;
    d.writable = ::access(node.c_str(), W_OK) == 0;
    devices.push_back(std::move(d));
  }
  return devices;
}

ProvisioningFacts read_provisioning(const std::string& root) {
  ProvisioningFacts p;
  p.limits_file = exists_in(root, {"etc/security/limits.d/95-teleop.conf"});
  p.udev_rules = exists_in(root, {"usr/lib/udev/rules.d/60-teleop.rules", "lib/udev/rules.d/60-teleop.rules",
                                  "etc/udev/rules.d/60-teleop.rules"});
  p.node_unit = exists_in(root, {"usr/lib/systemd/system/teleop-node@.service", "lib/systemd/system/teleop-node@.service",
                                 "etc/systemd/system/teleop-node@.service"});
  const passwd* user = ::getpwuid(::geteuid());
  p.user = user == nullptr ? std::to_string(::geteuid()) : user->pw_name;
  const group* teleop = ::getgrnam("teleop");
  p.group_exists = teleop != nullptr;
  if (teleop != nullptr) {
    // the groups this process has now: an `usermod -aG` takes effect at the next login
    std::vector<gid_t> groups(static_cast<size_t>(std::max(0, ::getgroups(0, nullptr))));
    const int n = ::getgroups(static_cast<int>(groups.size()), groups.data());
    groups.resize(static_cast<size_t>(std::max(0, n)));
    p.in_group = ::getegid() == teleop->gr_gid ||
                 std::find(groups.begin(), groups.end(), teleop->gr_gid) != groups.end();
  }
  return p;
}

}  // namespace teleop::doctor
