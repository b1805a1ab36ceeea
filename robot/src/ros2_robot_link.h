#pragma once
// The robot's ROS 2 topics as DDS endpoints on its own domain participant: a writer of
// std_msgs/Float64MultiArray commands, readers of sensor_msgs/JointState and (optionally)
// geometry_msgs/WrenchStamped. QoS as ROS 2's controllers and broadcasters need it on rmw_fastrtps
// and rmw_cyclonedds alike: the command writer reliable (a controller subscribes reliable, keep
// last 10), the readers best effort (they match reliable and best-effort publishers both).
// The participant is a teleop one (transports, discovery, security from `ros2.transport`), its
// endpoints are not. Samples arrive on Fast DDS's threads and reach the control loop through lock-free queues.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "teleop/common/joint_model.h"
#include "teleop/common/spsc_queue.h"
#include "teleop/robot/ros2_backend.h"
#include "teleop/transport/participant.h"

namespace teleop::robot {

/// One JointState, in the follower's joint order, stamped with its arrival (monotonic) and the
/// robot's header stamp.
struct RobotStateRecord {
  JointVector q_rad{};
  JointVector dq_radps{};
  JointVector tau_nm{};
  int64_t arrival_ns = 0;
  int64_t stamp_ns = 0;
};

/// One WrenchStamped, stamped with its arrival (monotonic).
struct RobotWrenchRecord {
  std::array<double, 3> force_n{};
  std::array<double, 3> torque_nm{};
  int64_t arrival_ns = 0;
};

class Ros2RobotLink {
 public:
  /// Joins the robot's domain and creates the endpoints. Throws std::runtime_error when DDS refuses.
  explicit Ros2RobotLink(const Ros2HardwareConfig& config);
  ~Ros2RobotLink();
  Ros2RobotLink(const Ros2RobotLink&) = delete;
  Ros2RobotLink& operator=(const Ros2RobotLink&) = delete;

  /// The newest state (or wrench) received since the last call; false when none came. Real-time safe.
  bool newest_state(RobotStateRecord& out);
  bool newest_wrench(RobotWrenchRecord& out);
  /// Sends the first `joints` values as the controller's command. Real-time safe.
  bool send(const JointVector& values);
  /// Waits up to `timeout_s` until the controller acknowledged what was sent (shutdown).
  void flush(double timeout_s);
  /// Controllers subscribed to the command topic.
  int command_readers() const;
  /// States refused: joints missing, unexpected or repeated, arrays too short, values not finite.
  uint64_t invalid_states() const { return invalid_states_.load(std::memory_order_relaxed); }
  /// Wrenches refused: another frame than ros2.wrench_frame, values not finite.
  uint64_t invalid_wrenches() const { return invalid_wrenches_.load(std::memory_order_relaxed); }
  /// Why the first state refused for its names was refused (setup time; "" if none was).
  std::string name_mismatch() const;

 private:
  struct Endpoints;
  class StateListener;
  class WrenchListener;

  void on_state(const void* sample);
  void on_wrench(const void* sample);

  Ros2HardwareConfig config_;
  // the queues outlive the endpoints whose listeners fill them
  SpscQueue<RobotStateRecord, 8> states_;
  SpscQueue<RobotWrenchRecord, 8> wrenches_;
  transport::Participant participant_;
  std::unique_ptr<Endpoints> dds_;
  std::atomic<uint64_t> invalid_states_{0};
  std::atomic<uint64_t> invalid_wrenches_{0};
  mutable std::mutex mismatch_mutex_;
  std::string mismatch_;
};

}  // namespace teleop::robot
