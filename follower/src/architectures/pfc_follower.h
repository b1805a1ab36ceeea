#pragma once
// pfc and pfc_tdpa at the follower: it tracks the leader's Cartesian commands through its end of
// the TDPA channel (passive_reference.h). pfc observes the energy balance (reported); pfc_tdpa's
// passivity controller slows the received twist, and the reference pose drifts with it.

#include <optional>

#include "follower_architecture.h"
#include "teleop/follower/passive_reference.h"
#include "teleop/runtime/tdpa_link.h"

namespace teleop::follower {

class PfcFollower final : public FollowerArchitecture {
 public:
  /// `corrects`: the passivity controller acts (pfc_tdpa); false: observe only (pfc).
  PfcFollower(transport::Participant& participant, const std::string& node_name, const std::string& arm, double cycle_s,
              bool corrects, const runtime::TdpaSettings& settings);

  bool cartesian() const override { return true; }
  const ValidCommand* correct(const ValidCommand& active, bool running, const control::Vector6& wrench) override;
  void restart() override { passive_.reset(); }
  double observed_energy_j() const override { return tdpa_.observed_energy_j(); }
  const runtime::TdpaLink* tdpa() const override { return &tdpa_; }
  double position_drift_m() const override { return passive_.position_drift_m(); }
  void fill_status(msg::NodeStatus& status) const override { status.tdpa_energy_j(tdpa_.observed_energy_j()); }
  void fill_report(runtime::NodeReport& report) const override;

 private:
  runtime::TdpaLink tdpa_;
  PassiveReference passive_;
  ValidCommand corrected_{};
};

}  // namespace teleop::follower
