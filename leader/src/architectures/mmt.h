#pragma once
// mmt (model-mediated) at the leader: the leader commands nobody; the twin couples to the device
// state the node publishes (so that writer decides whether the leader is in command), the operator
// feels the twin's constraint torque without the network's delay, and both the follower and the
// twin must be there for the leader to run.

#include "leader_architecture.h"

namespace teleop::leader {

class MmtLeader final : public LeaderArchitecture {
 public:
  explicit MmtLeader(const LeaderSetup& setup);

  bool cartesian() const override { return false; }
  WriterId authority_writer() const override { return device_state_.writer_id(); }
  const std::string& authority_topic() const override { return device_state_.topic_name(); }
  bool peers_fresh(int64_t now_ns, int64_t timeout_ns) const override {
    return twin_feedback_.age_ns(now_ns) < timeout_ns;
  }
  void send(const MappedDevice& /*device*/) override {}  // the node's device state is the command
  bool feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback, uint64_t& rejected) override;

 private:
  const LeaderConfig& config_;
  const transport::Subscription<msg::JointTorque>& twin_feedback_;
  const transport::Publication<msg::JointState>& device_state_;
};

}  // namespace teleop::leader
