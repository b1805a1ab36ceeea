#include "teleop/doctor/host_needs.h"

#include <algorithm>

#include "teleop/common/config.h"
#include "teleop/hand/hand_config.h"
#include "teleop/launcher/scenario.h"
#include "teleop/robot/canopen_backend.h"
#include "teleop/runtime/node_config.h"
#include "teleop/transport/participant_config.h"

namespace teleop::doctor {
namespace {

// a bus named by several joints or nodes is checked once
void add_can(HostNeeds& needs, CanNeed need) {
  const bool known = std::any_of(needs.can.begin(), needs.can.end(),
                                 [&](const CanNeed& c) { return c.interface == need.interface; });
  if (!known) needs.can.push_back(std::move(need));
}

// a robot's section (`hardware: canopen`, its drives on CAN buses)
void add_drive_buses(HostNeeds& needs, const ConfigNode& section, const ConfigNode& root, const std::string& node) {
  if (section.get_string("hardware", "mujoco") != "canopen") return;
  const auto spec = robot::parse_canopen_hardware(section);
  for (const robot::CanopenJointConfig& joint : spec->config().joints) {
    add_can(needs, {joint.bus, spec->config().bitrate_bps, node, root.file()});
  }
}

// the CAN buses of the nodes that have them: the hand's, a follower on CiA 402 drives, and a
// leader whose master arm is one (leader.device: robot_arm)
void add_can_buses(HostNeeds& needs, const ConfigNode& root, const std::string& node) {
  if (root.has("hand")) {
    const hand::HandNodeConfig hand = hand::parse_hand_config(root);
    add_can(needs, {hand.interface, hand.adapter.bitrate_bps, node, root.file()});
  }
  if (root.has("follower")) add_drive_buses(needs, root.child("follower"), root, node);
  if (root.has("leader")) {
    const ConfigNode leader = root.child("leader");
    if (leader.get_string("device", "") == "robot_arm") add_drive_buses(needs, leader.child("robot_arm"), root, node);
  }
}

void add_node(HostNeeds& needs, ConfigNode root, const std::vector<std::string>& sets) {
  for (const std::string& set : sets) root.apply_override(set);
  const runtime::NodeConfig node = runtime::parse_node_config(root.child("node"), "node");
  needs.realtime.push_back({node.name, root.file(), node.realtime});
  if (root.has("transport")) {
    const transport::ParticipantConfig dds = transport::parse_participant_config(root.child("transport"), node.name);
    needs.dds.push_back({node.name, root.file(), dds.interface_whitelist,
                         dds.discovery == transport::DiscoveryMode::kMulticast});
  }
  add_can_buses(needs, root, node.name);
}

}  // namespace

int HostNeeds::highest_priority() const {
  int highest = 0;
  for (const RealtimeNeed& r : realtime) {
    if (r.realtime.mode != runtime::RealtimeMode::kOff) highest = std::max(highest, r.realtime.priority);
  }
  return highest;
}

int HostNeeds::judged_priority() const {
  const int highest = highest_priority();
  return highest > 0 ? highest : runtime::RealtimeConfig{}.priority;
}

bool HostNeeds::realtime_required() const {
  return std::any_of(realtime.begin(), realtime.end(),
                     [](const RealtimeNeed& r) { return r.realtime.mode == runtime::RealtimeMode::kRequired; });
}

HostNeeds needs_of(const std::vector<std::string>& config_files) {
  HostNeeds needs;
  for (const std::string& file : config_files) {
    const ConfigNode root = ConfigNode::load_file(file);
    if (!root.has("scenario")) {
      add_node(needs, root, {});
      continue;
    }
    for (const launcher::NodeLaunch& launch : launcher::load_scenario(file).nodes) {
      add_node(needs, ConfigNode::load_file(launch.config), launch.sets);
    }
  }
  return needs;
}

}  // namespace teleop::doctor
