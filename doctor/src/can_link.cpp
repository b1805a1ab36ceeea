// A CAN interface as iproute2 reports it (host_reader.h). Its bitrate and controller state come
// over netlink only; `ip -details -json` is the kernel's own tool saying it, with a stable JSON
// form, on every Debian host.
#include <cctype>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "teleop/doctor/host_reader.h"

namespace teleop::doctor {

CanLink parse_ip_link(const std::string& name, const std::string& ip_json) {
  CanLink link;
  link.name = name;
  if (ip_json.find_first_not_of(" \t\r\n") == std::string::npos) return link;  // ip: "Device does not exist"
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

CanLink read_can_link(const std::string& name) {
  // an interface name has no shell characters (IFNAMSIZ, no '/' or space); refuse anything else
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
      throw std::runtime_error("not an interface name: '" + name + "'");
    }
  }
  const std::string command = "ip -details -json link show dev " + name + " 2>/dev/null";
  FILE* ip = ::popen(command.c_str(), "r");
  if (ip == nullptr) throw std::runtime_error("could not run ip (iproute2)");
  std::string out;
  char buffer[4096];
  while (const size_t n = std::fread(buffer, 1, sizeof(buffer), ip)) out.append(buffer, n);
  ::pclose(ip);
  return parse_ip_link(name, out);
}

}  // namespace teleop::doctor
