#pragma once
// A teleoperation architecture's part at the follower (docs/architectures.md): which command
// stream it waits for, and what it does to the command in force before the controller tracks it
// (pfc_tdpa: the passivity controller's correction), with what it adds to the status, report and
// trace. FollowerNode validates, watches and controls; its architecture, chosen by name
// (follower_architectures.h), does the rest. Whose commands arrive (the leader's or the twin's)
// is the configuration's (follower.command_source, implied by the architecture's CommandPath).
// Setup allocates (the channels); the per-cycle calls do not.

#include <teleop/msg/status.h>

#include <cmath>

#include "teleop/control/types.h"
#include "teleop/follower/command_validator.h"
#include "teleop/runtime/node_report.h"
#include "teleop/runtime/tdpa_link.h"

namespace teleop::follower {

class FollowerArchitecture {
 public:
  virtual ~FollowerArchitecture() = default;

  /// The follower waits for Cartesian commands (the joint stream is optional), else the reverse.
  virtual bool cartesian() const = 0;
  /// This cycle's correction of `active` (the command in force, as received) given the estimated
  /// external wrench; null when the controller tracks what it had (`running`: the robot follows
  /// the commands, no hold).
  virtual const ValidCommand* correct(const ValidCommand& active, bool running, const control::Vector6& wrench) = 0;
  /// The command source was lost, or a reflex holds: the channel's session ends.
  virtual void restart() {}

  /// The channel's observed energy [J]; NaN without a TDPA channel.
  virtual double observed_energy_j() const { return std::nan(""); }
  /// The channel's passivity link (its controller's work is traced); null without one.
  virtual const runtime::TdpaLink* tdpa() const { return nullptr; }
  /// How far the reference drifted from the received poses [m]; 0 without a correction.
  virtual double position_drift_m() const { return 0.0; }
  virtual void fill_status(msg::NodeStatus& /*status*/) const {}
  virtual void fill_report(runtime::NodeReport& /*report*/) const {}
};

}  // namespace teleop::follower
