#pragma once
// The follower's end of the TDPA channel (pfc_tdpa, docs/architectures.md): the Cartesian
// command's twist is the velocity the channel delivers; the impedance's spring, pulling the
// reference back, is the force. When the observed energy would go negative the passivity
// controller slows the delivered velocity (v_out = v + beta f), and the reference pose moves with
// the corrected velocity: the difference accumulates as a drift (position, rotation vector) added
// to every later target, which is what makes the correction real for a pose-tracking controller.
// apply() is real-time safe.

#include "teleop/control/types.h"
#include "teleop/follower/command_validator.h"
#include "teleop/teleoperation/tdpa_link.h"

namespace teleop::follower {

class PassiveReference {
 public:
  PassiveReference(teleoperation::TdpaLink& link, double cycle_s) : link_(&link), h_(cycle_s) {}

  /// Corrects `command` (Cartesian, as received) into `corrected` given the impedance's last
  /// pose error; sends this end's energy packet.
  void apply(const ValidCommand& command, const control::Vector6& pose_error, ValidCommand& corrected);
  /// A new session (the command source was lost): energies and drift back to zero.
  void reset();

  /// |drift| of the position [m] and of the rotation [rad].
  double position_drift_m() const { return drift_.head<3>().norm(); }
  double rotation_drift_rad() const { return drift_.tail<3>().norm(); }

 private:
  teleoperation::TdpaLink* link_;
  double h_;
  control::Vector6 drift_ = control::Vector6::Zero();
};

}  // namespace teleop::follower
