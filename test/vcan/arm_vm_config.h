#pragma once
// What the VM tests of an arm of CiA 402 drives share (the follower's arm, a leader's master arm):
// the four interfaces of the arm's buses, a shipped configuration rewritten for the VM (its buses
// on those interfaces, its model paths absolute, the drives' timing a starved VM keeps), and a
// child's output kept in a log for the failure messages.

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace teleop::can::test {

// The VM's timing of the drives and their master: heartbeats every 20 ms, lost after 400 ms.
constexpr int kVmHeartbeatMs = 20;
constexpr int kVmLostAfterMs = 400;

/// The four interfaces of the arm's buses: vcan0..vcan3 in the VM, the harness's on a host.
inline std::vector<std::string> arm_interfaces() {
  std::vector<std::string> names;
  if (const char* e = std::getenv("TELEOP_VCAN_IFS"); e != nullptr && *e != '\0') {
    std::istringstream in(e);
    for (std::string n; in >> n;) names.push_back(n);
  }
  if (names.size() < 4) names = {"vcan0", "vcan1", "vcan2", "vcan3"};
  return names;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Replaces `from` (which must be there: the shipped file changed otherwise) by `to`, everywhere.
inline void replace_all(std::string& text, const std::string& from, const std::string& to) {
  if (text.find(from) == std::string::npos) throw std::runtime_error("update this test: no '" + from + "' in the config");
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

/// The shipped configuration at `shipped` (an arm's drives on can0..can3, `rate_hz: 1000`) for the
/// VM: its buses on arm_interfaces(), its model paths absolute, the node at `rate_hz`, unicast
/// discovery (no multicast on the VM's loopback), the VM's heartbeats and consumer times, and room
/// for a starved loop before the feedback counts as stale and for the slow start-up.
inline std::string arm_config_for_vm(const std::string& shipped, int rate_hz) {
  std::string text = read_text(shipped);
  const std::vector<std::string> names = arm_interfaces();
  for (size_t b = 0; b < 4; ++b) replace_all(text, "bus: can" + std::to_string(b) + ",", "bus: " + names[b] + ",");
  replace_all(text, "../models/", std::filesystem::path(shipped).parent_path().string() + "/../models/");
  replace_all(text, "  rate_hz: 1000\n", "  rate_hz: " + std::to_string(rate_hz) + "\n");
  replace_all(text, "initial_peers: []", "initial_peers: [\"127.0.0.1\"]");
  replace_all(text, "    mode: multicast ", "    mode: peers ");
  const std::string heartbeat = std::to_string(kVmHeartbeatMs), lost = std::to_string(kVmLostAfterMs);
  replace_all(text, "master_heartbeat_ms: 10\n", "master_heartbeat_ms: " + heartbeat + "\n");
  replace_all(text, "drive_heartbeat_ms: 10 ", "drive_heartbeat_ms: " + heartbeat + " ");
  replace_all(text, "master_lost_after_ms: 50 ", "master_lost_after_ms: " + lost + " ");
  replace_all(text, "drive_lost_after_ms: 50 ", "drive_lost_after_ms: " + lost + " ");
  replace_all(text, "state_timeout_ms: 5 ", "state_timeout_ms: 200 ");
  replace_all(text, "sdo_timeout_ms: 200 ", "sdo_timeout_ms: 2000 ");
  replace_all(text, "enable_timeout_s: 1 ", "enable_timeout_s: 30 ");
  return text;
}

/// "exec PROGRAM ARGS > LOG 2>&1" as a child's argv: its output kept for the failure messages.
inline std::vector<std::string> logged(const std::vector<std::string>& argv, const std::string& log) {
  std::string cmd = "exec";
  for (const std::string& a : argv) cmd += " '" + a + "'";
  return {"sh", "-c", cmd + " > '" + log + "' 2>&1"};
}

inline int64_t realtime_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace teleop::can::test
