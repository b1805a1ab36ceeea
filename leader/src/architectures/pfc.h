#pragma once
// pfc and pfc_tdpa at the leader (position-force control): the device's flange, mapped into the
// follower's frame, goes out as a Cartesian impedance command, and the operator feels the
// follower's estimated external wrench as J_d^T F. The wrench passes the leader's port of the
// TDPA channel: pfc only observes its energy balance (reported), pfc_tdpa lets the passivity
// controller correct it (docs/tdpa.md).

#include "leader_architecture.h"
#include "teleop/runtime/tdpa_link.h"

namespace teleop::leader {

class PfcLeader final : public LeaderArchitecture {
 public:
  /// `corrects`: the passivity controller acts (pfc_tdpa); false: observe only (pfc).
  PfcLeader(const LeaderSetup& setup, bool corrects);

  bool cartesian() const override { return true; }
  WriterId authority_writer() const override { return command_.writer_id(); }
  const std::string& authority_topic() const override { return command_.topic_name(); }
  void receive() override { tdpa_.receive(); }
  void restart() override { tdpa_.reset(); }
  void send(const MappedDevice& device) override;
  bool feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback, uint64_t& rejected) override;
  double observed_energy_j() const override { return tdpa_.observed_energy_j(); }
  const runtime::TdpaLink* tdpa() const override { return &tdpa_; }
  void fill_status(msg::NodeStatus& status) const override { status.tdpa_energy_j(tdpa_.observed_energy_j()); }
  void report_command(runtime::NodeReport& report) const override { report.add(command_); }
  void report_channel(runtime::NodeReport& report) const override { tdpa_.fill_report(report); }

 private:
  const LeaderConfig& config_;
  const transport::Subscription<msg::WrenchStamped>& follower_wrench_;
  transport::Publication<msg::CartesianCommand> command_;
  runtime::TdpaLink tdpa_;
};

}  // namespace teleop::leader
