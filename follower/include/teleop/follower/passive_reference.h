#pragma once
// The follower's end of the TDPA channel (pfc_tdpa, docs/architectures.md): the Cartesian
// command's twist is the velocity the channel delivers; the estimated external wrench, which the
// channel carries back to the leader, is the force. When the observed energy would go negative the passivity
// controller slows the delivered velocity (v_out = v + beta f), and the reference pose moves with
// the corrected velocity: the difference accumulates as a drift (position, rotation vector) added
// to every later target, which is what makes the correction real for a pose-tracking controller.
// With teleoperation.tdpa.drift_time_constant_s the drift is asked back through the passivity
// controller as far as the observed energy allows (control/drift_compensation.h).
// apply() is real-time safe.

#include "teleop/control/drift_compensation.h"
#include "teleop/control/types.h"
#include "teleop/follower/command_validator.h"
#include "teleop/runtime/architecture.h"
#include "teleop/runtime/tdpa_link.h"

namespace teleop::follower {

class PassiveReference {
 public:
  PassiveReference(runtime::TdpaLink& link, double cycle_s, const runtime::TdpaSettings& settings);

  /// Corrects `command` (Cartesian, as received) into `corrected` given this cycle's estimated
  /// external wrench (base frame, the one published to the leader); sends this end's energy packet.
  void apply(const ValidCommand& command, const control::Vector6& wrench, ValidCommand& corrected);
  /// A new session (the command source was lost): energies back to zero. The drift stays: it is
  /// where the reference is relative to the leader's commands, and dropping it would move the
  /// reference by all of it at once (into a wall the follower rests on: a force step). It is
  /// returned as before, in free motion, as the new session's energy allows.
  void reset();

  /// |drift| of the position [m] and of the rotation [rad].
  double position_drift_m() const;
  double rotation_drift_rad() const;

 private:
  runtime::TdpaLink* link_;
  double h_;
  control::DriftCompensator drift_;
};

}  // namespace teleop::follower
