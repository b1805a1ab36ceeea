// A CAN interface as iproute2 reports it (host_reader.h). Its bitrate and controller state come
// over netlink only; `ip -details -json` is the kernel's own tool saying it, with a stable JSON
// form, on every Debian host.
#include <poll.h>

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "teleop/doctor/host_reader.h"
#include "teleop/launcher/child_process.h"
#include "teleop/launcher/launcher.h"

namespace teleop::doctor {

CanLink parse_ip_link(const std::string& name, const std::string& ip_json) {
  CanLink link;
  link.name = name;
  if (ip_json.find_first_not_of(" \t\r\n") == std::string::npos) return link;  // no answer: no such interface
  const nlohmann::json all = nlohmann::json::parse(ip_json, nullptr, false);
  if (all.is_discarded() || !all.is_array()) throw std::runtime_error("ip -json link: not a JSON array: " + ip_json);
  for (const nlohmann::json& entry : all) {
    if (entry.value("ifname", "") != name) continue;
    link.exists = true;
    for (const nlohmann::json& flag : entry.value("flags", nlohmann::json::array())) {
      if (flag == "UP") link.up = true;
    }
    const nlohmann::json info = entry.value("linkinfo", nlohmann::json::object());
    link.kind = info.value("info_kind", "");
    const nlohmann::json data = info.value("info_data", nlohmann::json::object());
    link.state = data.value("state", "");
    link.bitrate_bps = data.value("bittiming", nlohmann::json::object()).value("bitrate", uint64_t{0});
  }
  return link;
}

namespace {

// runs `ip` found on PATH (no shell: a shell may prefer its own applet, as busybox's does) and
// returns its exit status and what it wrote to stdout and stderr
int run_ip(const std::vector<std::string>& args, std::string& out) {
  std::vector<std::string> argv = {launcher::find_executable("ip", "")};
  argv.insert(argv.end(), args.begin(), args.end());
  launcher::ChildProcess ip = launcher::ChildProcess::spawn(argv);
  while (ip.output_fd() >= 0) {
    pollfd readable{ip.output_fd(), POLLIN, 0};
    ::poll(&readable, 1, 1000);
    ip.read_output([&](std::string_view line) { out.append(line).append("\n"); });
  }
  return ip.wait_for(5000).value_or(128);
}

}  // namespace

CanLink read_can_link(const std::string& name) {
  std::string out;
  int status = 0;
  try {
    status = run_ip({"-details", "-json", "link", "show", "dev", name}, out);
  } catch (const std::runtime_error& e) {  // no ip on PATH, or it could not be started
    CanLink link;
    link.name = name;
    link.error = std::string("ip (iproute2) could not be run: ") + e.what();
    return link;
  }
  if (status == 0) return parse_ip_link(name, out);
  CanLink link;
  link.name = name;
  // ip's own words for an interface that is not there; anything else is ip failing
  if (out.find("does not exist") == std::string::npos) link.error = "ip -details -json link: " + out;
  return link;
}

}  // namespace teleop::doctor
