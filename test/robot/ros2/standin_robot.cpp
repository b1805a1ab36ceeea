// teleop_ros2_standin_robot: a ROS 2 robot for the tests, on another DDS. Cyclone DDS (the DDS of
// rmw_cyclonedds, through its C API and idlc's types of the IDL rosidl makes of common_interfaces)
// carries what ros2_control would: a forward_command_controller's std_msgs/Float64MultiArray in,
// joint_state_broadcaster's sensor_msgs/JointState out at 1 kHz, and (--wrench-topic) the contact
// wrench at the flange in the base frame as a geometry_msgs/WrenchStamped, as a Franka's broadcaster
// publishes its estimate. A MuJoCo arm is the robot's
// physics, gravity-compensated as a Franka is; an effort command is its torque, a position or
// velocity command is tracked by the robot's own joint PD. Like a lab's robot configured as
// docs/robots.md asks, it holds its pose when commands stop for --command-timeout-ms.
//
// For the tests it can publish its joints in another order with a joint more (--shuffle), and
// stop publishing its state for a while (--pause-at-s after its first command, --pause-ms). It
// prints what happens.

#include <dds/dds.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include "geometry_msgs/msg/WrenchStamped_.h"
#include "sensor_msgs/msg/JointState_.h"
#include "std_msgs/msg/Float64MultiArray_.h"
#include "teleop/common/clock.h"
#include "teleop/robot/mujoco_hardware.h"

namespace {

using teleop::JointVector;

// SIGTERM or SIGINT: the robot stops at the end of its cycle and prints its summary
std::atomic<bool> g_stop{false};
void request_stop(int) { g_stop = true; }

struct Options {
  std::string model;
  std::string keyframe;
  std::string interface = "effort";
  std::vector<std::string> joints;
  bool shuffle = false;
  std::string extra_joint = "standin_gripper_joint";
  int domain = 0;
  std::string command_topic;
  std::string state_topic = "/joint_states";
  std::string wrench_topic;
  double command_timeout_ms = 100;
  double pause_at_s = -1;  // after the first command
  double pause_ms = 0;
  double duration_s = 10;
  double kp = 600;  // the robot's own joint position loop [N m/rad], and its damping [N m s/rad]
  double kd = 40;
};

// Cyclone on loopback, discovery by unicast to this host's ports (multicast is not everywhere)
constexpr const char* kLoopback =
    "<General><Interfaces><NetworkInterface address=\"127.0.0.1\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>auto</ParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>";

// the order the state lists the joints in: as configured, or reversed behind a gripper's joint
std::vector<std::string> published_names(const Options& o) {
  std::vector<std::string> names = o.joints;
  if (!o.shuffle) return names;
  std::reverse(names.begin(), names.end());
  names.insert(names.begin(), o.extra_joint);
  return names;
}

class StateWriter {
 public:
  StateWriter(dds_entity_t writer, const std::vector<std::string>& names, size_t joints, bool shuffled)
      : writer_(writer), names_(names), shuffled_(shuffled), joints_(joints) {
    for (auto& name : names_) pointers_.push_back(name.data());
    values_.assign(3 * names_.size(), 0.0);
    sample_.name_ = {static_cast<uint32_t>(names_.size()), static_cast<uint32_t>(names_.size()), pointers_.data(), false};
    const auto seq = [&](size_t k) {
      return dds_sequence_double{static_cast<uint32_t>(names_.size()), static_cast<uint32_t>(names_.size()),
                                 values_.data() + k * names_.size(), false};
    };
    sample_.position_ = seq(0);
    sample_.velocity_ = seq(1);
    sample_.effort_ = seq(2);
    sample_.header_.frame_id_ = frame_;
  }
  // `stamp_ns`: when the state was measured, on the robot's clock
  void write(const teleop::robot::ArmState& s, int64_t stamp_ns) {
    const size_t n = names_.size();
    for (size_t i = 0; i < joints_; ++i) {
      // configured joint i sits at i, or (shuffled) behind the gripper in reverse
      const size_t k = shuffled_ ? n - 1 - i : i;
      values_[k] = s.q_rad[i];
      values_[n + k] = s.dq_radps[i];
      values_[2 * n + k] = s.tau_measured_nm[i];
    }
    sample_.header_.stamp_ = {static_cast<int32_t>(stamp_ns / 1'000'000'000), static_cast<uint32_t>(stamp_ns % 1'000'000'000)};
    dds_write(writer_, &sample_);
  }

 private:
  dds_entity_t writer_;
  std::vector<std::string> names_;
  bool shuffled_;
  size_t joints_;
  std::vector<char*> pointers_;
  std::vector<double> values_;
  char frame_[1] = {};
  sensor_msgs_msg_dds__JointState_ sample_{};
};

// the MuJoCo contact wrench at the flange, base frame "fr3_link0"
class WrenchWriter {
 public:
  explicit WrenchWriter(dds_entity_t writer) : writer_(writer) { sample_.header_.frame_id_ = frame_; }
  void write(const teleop::robot::ArmState& s) {
    const auto& f = s.force_ext_n;
    const auto& t = s.torque_ext_nm;
    sample_.wrench_.force_ = {f[0], f[1], f[2]};
    sample_.wrench_.torque_ = {t[0], t[1], t[2]};
    dds_write(writer_, &sample_);
  }

 private:
  dds_entity_t writer_;
  char frame_[10] = "fr3_link0";
  geometry_msgs_msg_dds__WrenchStamped_ sample_{};
};

// the newest command, and when it came
struct CommandIntake {
  dds_entity_t reader;
  JointVector values{};
  int64_t last_ns = 0;
  uint64_t received = 0;
  uint64_t wrong_size = 0;
  // cycles while commanded that found no new command (the last one acted again), and that found
  // more than one (all but the newest were never applied)
  uint64_t cycles_without = 0;
  uint64_t cycles_with_several = 0;

  // returns how many commands arrived since the last cycle
  uint64_t take(size_t joints, int64_t now_ns) {
    const uint64_t before = received;
    void* samples[1] = {nullptr};
    dds_sample_info_t info[1];
    while (dds_take(reader, samples, info, 1, 1) > 0) {
      const auto* c = static_cast<const std_msgs_msg_dds__Float64MultiArray_*>(samples[0]);
      if (info[0].valid_data && c->data_._length == joints) {
        std::copy_n(c->data_._buffer, joints, values.begin());
        last_ns = now_ns;
        ++received;
      } else if (info[0].valid_data) {
        ++wrong_size;
      }
      dds_return_loan(reader, samples, 1);
      samples[0] = nullptr;
    }
    return received - before;
  }

  void count(uint64_t taken) {
    if (taken == 0) ++cycles_without;
    if (taken > 1) ++cycles_with_several;
  }
};

// the torque the robot applies on top of its gravity compensation
JointVector robot_torque(const Options& o, const JointVector& command, const teleop::robot::ArmState& s, size_t n) {
  JointVector tau{};
  for (size_t i = 0; i < n; ++i) {
    if (o.interface == "effort") tau[i] = command[i];
    if (o.interface == "position") tau[i] = o.kp * (command[i] - s.q_rad[i]) - o.kd * s.dq_radps[i];
    if (o.interface == "velocity") tau[i] = o.kd * (command[i] - s.dq_radps[i]);
  }
  return tau;
}

JointVector hold_torque(const Options& o, const JointVector& hold_q, const teleop::robot::ArmState& s, size_t n) {
  JointVector tau{};
  for (size_t i = 0; i < n; ++i) tau[i] = o.kp * (hold_q[i] - s.q_rad[i]) - o.kd * s.dq_radps[i];
  return tau;
}

double peak_speed(const teleop::robot::ArmState& s, size_t n) {
  double peak = 0;
  for (size_t i = 0; i < n; ++i) peak = std::max(peak, std::abs(s.dq_radps[i]));
  return peak;
}

int run(const Options& o) {
  teleop::robot::MujocoHardwareConfig model;
  model.model_path = o.model;
  model.keyframe = o.keyframe;
  model.period_s = 0.001;
  teleop::robot::MujocoHardware arm(model);
  const size_t n = arm.joints();
  if (o.joints.size() != n) {
    std::fprintf(stderr, "standin: --joints names %zu joints, the model's arm has %zu\n", o.joints.size(), n);
    return 2;
  }

  const auto domain = static_cast<dds_domainid_t>(o.domain);
  const dds_entity_t cyclone_domain = dds_create_domain(domain, kLoopback);
  const dds_entity_t participant = dds_create_participant(domain, nullptr, nullptr);
  // what ros2_control's controllers and broadcasters use: rclcpp's SystemDefaultsQoS, reliable, keep last 10
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  const dds_entity_t state_topic =
      dds_create_topic(participant, &sensor_msgs_msg_dds__JointState__desc, ("rt" + o.state_topic).c_str(), nullptr, nullptr);
  const dds_entity_t command_topic = dds_create_topic(participant, &std_msgs_msg_dds__Float64MultiArray__desc,
                                                      ("rt" + o.command_topic).c_str(), nullptr, nullptr);
  StateWriter states(dds_create_writer(participant, state_topic, qos, nullptr), published_names(o), n, o.shuffle);
  CommandIntake commands{dds_create_reader(participant, command_topic, qos, nullptr)};
  std::optional<WrenchWriter> wrenches;
  if (!o.wrench_topic.empty()) {
    const dds_entity_t topic = dds_create_topic(participant, &geometry_msgs_msg_dds__WrenchStamped__desc,
                                                ("rt" + o.wrench_topic).c_str(), nullptr, nullptr);
    wrenches.emplace(dds_create_writer(participant, topic, qos, nullptr));
  }
  dds_delete_qos(qos);

  teleop::robot::ArmState s;
  (void)arm.read(s);
  JointVector hold_q = s.q_rad;
  bool holding = true;  // until the first command
  bool stop_reported = true;
  uint64_t timeouts = 0;
  int64_t first_command_ns = 0;
  bool pause_reported = false;
  const int64_t start_ns = teleop::monotonic_now_ns();
  // the robot's clock is its simulation's: a cycle the host ran late still measured 1 ms later
  const int64_t epoch_ns = teleop::system_now_ns();
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  std::printf("standin: %s robot of %zu joints on domain %d, commands on %s\n", o.interface.c_str(), n, o.domain,
              o.command_topic.c_str());
  std::fflush(stdout);
  std::signal(SIGTERM, request_stop);
  std::signal(SIGINT, request_stop);
  for (int64_t cycle = 0; cycle < static_cast<int64_t>(o.duration_s * 1000) && !g_stop; ++cycle) {
    next.tv_nsec += 1'000'000;
    if (next.tv_nsec >= 1'000'000'000) {
      next.tv_nsec -= 1'000'000'000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    const int64_t now = teleop::monotonic_now_ns();
    const uint64_t taken = commands.take(n, now);
    const bool timed_out = commands.received == 0 || static_cast<double>(now - commands.last_ns) * 1e-6 > o.command_timeout_ms;
    if (timed_out && !holding) {
      holding = true;
      stop_reported = false;
      hold_q = s.q_rad;
      ++timeouts;
      std::printf("standin: command timeout: holding %.1f ms after the last command\n",
                  static_cast<double>(now - commands.last_ns) * 1e-6);
      std::fflush(stdout);
    } else if (!timed_out && holding) {
      holding = false;
      if (first_command_ns == 0) first_command_ns = now;
      std::printf("standin: commanded at %.3f s\n", static_cast<double>(now - start_ns) * 1e-9);
      std::fflush(stdout);
    }
    if (!holding) commands.count(taken);
    const JointVector tau = holding ? hold_torque(o, hold_q, s, n) : robot_torque(o, commands.values, s, n);
    (void)arm.write(tau);
    (void)arm.read(s);
    if (holding && !stop_reported && peak_speed(s, n) < 0.01) {
      stop_reported = true;
      std::printf("standin: stopped %.1f ms after the last command\n", static_cast<double>(now - commands.last_ns) * 1e-6);
      std::fflush(stdout);
    }
    const double t_s = static_cast<double>(now - first_command_ns) * 1e-9;
    const bool paused = first_command_ns != 0 && o.pause_at_s >= 0 && t_s >= o.pause_at_s && t_s < o.pause_at_s + o.pause_ms * 1e-3;
    if (paused && !pause_reported) {
      pause_reported = true;
      std::printf("standin: state paused for %.0f ms\n", o.pause_ms);
      std::fflush(stdout);
    }
    if (!paused) states.write(s, epoch_ns + (cycle + 1) * 1'000'000);
    if (!paused && wrenches) wrenches->write(s);
  }
  std::printf("standin: commands %llu, wrong size %llu, timeouts %llu, cycles without a new command %llu, with several %llu\n",
              static_cast<unsigned long long>(commands.received), static_cast<unsigned long long>(commands.wrong_size),
              static_cast<unsigned long long>(timeouts), static_cast<unsigned long long>(commands.cycles_without),
              static_cast<unsigned long long>(commands.cycles_with_several));
  dds_delete(participant);
  dds_delete(cyclone_domain);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"a ROS 2 robot on Cyclone DDS for teleop's tests: a MuJoCo arm behind ros2_control's topics"};
  app.add_option("--model", o.model, "the MJCF scene of the arm")->required();
  app.add_option("--keyframe", o.keyframe, "the keyframe to start from");
  app.add_option("--interface", o.interface, "what the command is")->check(CLI::IsMember({"effort", "position", "velocity"}));
  app.add_option("--joints", o.joints, "the joint names, in the arm's order")->required()->delimiter(',');
  app.add_flag("--shuffle", o.shuffle, "publish the joints reversed, behind a gripper's joint");
  app.add_option("--extra-joint", o.extra_joint, "the gripper's joint name (--shuffle)");
  app.add_option("--domain", o.domain, "the DDS domain")->required();
  app.add_option("--command-topic", o.command_topic, "the controller's command topic (default by --interface)");
  app.add_option("--state-topic", o.state_topic, "the joint state topic");
  app.add_option("--wrench-topic", o.wrench_topic, "publish the flange's contact wrench here");
  app.add_option("--command-timeout-ms", o.command_timeout_ms, "hold the pose when commands stop this long");
  app.add_option("--pause-at-s", o.pause_at_s, "stop publishing the state this long after the first command");
  app.add_option("--pause-ms", o.pause_ms, "for this long");
  app.add_option("--duration-s", o.duration_s, "how long the robot runs");
  CLI11_PARSE(app, argc, argv);
  if (o.command_topic.empty()) o.command_topic = "/forward_" + o.interface + "_controller/commands";
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "standin: %s\n", e.what());
    return 1;
  }
}
