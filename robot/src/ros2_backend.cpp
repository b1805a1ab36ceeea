#include "teleop/robot/ros2_backend.h"

#include <algorithm>

#include "ros2_hardware.h"

namespace teleop::robot {
namespace {

const char* interface_name(Ros2CommandInterface interface) {
  switch (interface) {
    case Ros2CommandInterface::kEffort: return "effort";
    case Ros2CommandInterface::kPosition: return "position";
    case Ros2CommandInterface::kVelocity: return "velocity";
  }
  return "effort";
}

// a per-joint list, given for every joint or not at all
std::vector<double> joint_list(const ConfigNode& ros2, const std::string& key, size_t joints, Range range) {
  std::vector<double> values = ros2.get_double_list(key, range);
  if (!values.empty() && values.size() != joints) {
    throw ros2.error(key, "has " + std::to_string(values.size()) + " values for " + std::to_string(joints) + " joints");
  }
  return values;
}

void check_names(const ConfigNode& ros2, const Ros2HardwareConfig& config) {
  std::vector<std::string> all = config.joints;
  all.insert(all.end(), config.ignored_joints.begin(), config.ignored_joints.end());
  for (size_t i = 0; i < all.size(); ++i) {
    if (std::find(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(i), all[i]) != all.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw ros2.error(i < config.joints.size() ? "joints" : "ignored_joints", "names " + all[i] + " twice");
    }
  }
}

// the joints by name, those ignored, and what the robot can do per joint
void parse_joints(const ConfigNode& ros2, Ros2HardwareConfig& config) {
  config.joints = ros2.get_string_list("joints");
  if (config.joints.empty()) throw ros2.error("joints", "is required: the robot's joint names in the follower's order");
  if (config.joints.size() > kMaxJoints) throw ros2.error("joints", "names more than " + std::to_string(kMaxJoints) + " joints");
  config.ignored_joints = ros2.get_string_list("ignored_joints");
  check_names(ros2, config);
  const size_t n = config.joints.size();
  config.q_min_rad = joint_list(ros2, "q_min_rad", n, {-1e3, 1e3});
  config.q_max_rad = joint_list(ros2, "q_max_rad", n, {-1e3, 1e3});
  config.max_torque_nm = joint_list(ros2, "max_torque_nm", n, {1e-6, 1e6});
}

// a ROS 2 topic name of the section, checked; "" only where there is none by default (optional)
std::string topic(const ConfigNode& ros2, const std::string& key, const std::string& fallback) {
  const std::string name = ros2.get_string(key, fallback);
  if (name.empty() ? !fallback.empty() : !name.starts_with('/')) {
    throw ros2.error(key, "is a ROS 2 topic name: it starts with '/' (" + name + ")");
  }
  return name;
}

// the command interface and the topics, named by default as ros2_control's examples name them
void parse_topics(const ConfigNode& ros2, Ros2HardwareConfig& config) {
  const std::string interface = ros2.get_choice("interface", {"effort", "position", "velocity"}, "effort");
  for (auto candidate : {Ros2CommandInterface::kEffort, Ros2CommandInterface::kPosition, Ros2CommandInterface::kVelocity}) {
    if (interface == interface_name(candidate)) config.interface = candidate;
  }
  config.command_topic = topic(ros2, "command_topic", "/forward_" + interface + "_controller/commands");
  config.state_topic = topic(ros2, "state_topic", config.state_topic);
  config.wrench_topic = topic(ros2, "wrench_topic", "");
  config.wrench_frame = ros2.get_string("wrench_frame", "");
}

}  // namespace

transport::ParticipantConfig Ros2HardwareConfig::default_participant() {
  transport::ParticipantConfig participant;
  participant.domain_id = 0;
  participant.name = "teleop_follower_robot";
  return participant;
}

std::unique_ptr<RobotHardware> Ros2HardwareSpec::make(double period_s) const {
  (void)period_s;  // the robot's controller manager keeps its own rate
  return std::make_unique<Ros2Hardware>(config_);
}

std::shared_ptr<const Ros2HardwareSpec> parse_ros2_hardware(const ConfigNode& section) {
  const ConfigNode ros2 = section.child("ros2");
  Ros2HardwareConfig config;
  parse_joints(ros2, config);
  parse_topics(ros2, config);
  if (const auto bus = ros2.optional_child("transport")) {
    config.participant = transport::parse_participant_config(*bus, config.participant.name);
    if (config.participant.impairment.enabled()) throw bus->error("impairment", "the robot's own bus is not impaired");
  }
  config.state_timeout_s = ros2.get_double("state_timeout_ms", {0.5, 1000}, config.state_timeout_s * 1e3) * 1e-3;
  config.connect_timeout_s = ros2.get_double("connect_timeout_s", {0.1, 600}, config.connect_timeout_s);
  config.phase_lock = ros2.get_bool("phase_lock", config.phase_lock);
  config.phase_lock_lead_s = ros2.get_double("phase_lock_lead_us", {0, 900}, config.phase_lock_lead_s * 1e6) * 1e-6;
  config.gravity_compensated = ros2.get_bool("gravity_compensated", true);
  if (config.interface == Ros2CommandInterface::kEffort && !config.gravity_compensated) {
    throw ros2.error("gravity_compensated", "must be true for interface: effort (the follower holds it with zero effort)");
  }
  return std::make_shared<const Ros2HardwareSpec>(config);
}

void add_ros2_backend(HardwareRegistry& registry) {
  registry.add("ros2", [](const ConfigNode& section) { return parse_ros2_hardware(section); });
}

}  // namespace teleop::robot
