#pragma once
// A teleoperation architecture's part at the leader (docs/architectures.md): the channel it sends
// the mapped device on, the writer that decides whether this leader is in command, the feedback the
// operator feels and what it adds to the status, report and trace. LeaderNode reads, maps and
// renders the device; its architecture, chosen by name (leader_architectures.h), does the rest.
// Setup allocates (the channels); the per-cycle calls (receive, send, feedback, ...) do not.

#include <teleop/msg/arm.h>

#include <cmath>
#include <string>

#include "../arm_kinematics.h"
#include "../cartesian_mapping.h"
#include "../leader_config.h"
#include "teleop/common/joint_model.h"
#include "teleop/runtime/node_report.h"
#include "teleop/runtime/tdpa_link.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::leader {

/// The peers' streams the node keeps whatever the architecture (it reports them all).
struct LeaderPeers {
  transport::Subscription<msg::JointState>& follower_state;
  transport::Subscription<msg::WrenchStamped>& follower_wrench;
  transport::Subscription<msg::JointTorque>& twin_feedback;
};

/// What an architecture is built from. `config` outlives it (the node's own copy).
struct LeaderSetup {
  const LeaderConfig& config;
  runtime::NodeContext& context;
  double period_s;
  LeaderPeers peers;
  /// The device's mapped state, which the node publishes every cycle (the twin couples to it).
  const transport::Publication<msg::JointState>& device_state;
};

/// This cycle's device, mapped into the follower's space by the node.
struct MappedDevice {
  const JointVector& q_cmd;
  const JointVector& dq_cmd;
  /// The Cartesian mapping, run this cycle when the architecture is cartesian().
  const CartesianMapping& cartesian;
  /// The device's kinematics at its pose of this cycle; null without leader.arm_model and for a
  /// Cartesian device (DeviceSpec::cartesian()).
  const ArmKinematics* kinematics;
};

class LeaderArchitecture {
 public:
  virtual ~LeaderArchitecture() = default;

  /// The device is mapped in Cartesian space: the node runs its CartesianMapping every cycle.
  virtual bool cartesian() const = 0;
  /// The writer whose commands decide whether this leader is in command, and its topic's name
  /// (runtime/command_authority.h).
  virtual WriterId authority_writer() const = 0;
  virtual const std::string& authority_topic() const = 0;

  /// Whether the peers this architecture needs besides the follower's state are there.
  virtual bool peers_fresh(int64_t /*now_ns*/, int64_t /*timeout_ns*/) const { return true; }
  /// Takes what arrived on the architecture's own channels.
  virtual void receive() {}
  /// The follower follows again after a hold: a new session on the channel.
  virtual void restart() {}
  /// Sends this cycle's command.
  virtual void send(const MappedDevice& device) = 0;
  /// The device torque the architecture renders this cycle, into `feedback` (the first
  /// config.joints); false when its source is missing or stale. Counts samples it refuses.
  virtual bool feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback, uint64_t& rejected) = 0;

  /// The channel's observed energy [J]; NaN without a TDPA channel.
  virtual double observed_energy_j() const { return std::nan(""); }
  /// The channel's passivity link (its controller's work is traced); null without one.
  virtual const runtime::TdpaLink* tdpa() const { return nullptr; }
  virtual void fill_status(msg::NodeStatus& /*status*/) const {}
  /// The command writer's line of the report.
  virtual void report_command(runtime::NodeReport& /*report*/) const {}
  /// The channel's lines and counters, after the peers'.
  virtual void report_channel(runtime::NodeReport& /*report*/) const {}
};

}  // namespace teleop::leader
