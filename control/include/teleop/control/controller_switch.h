#pragma once
// Run-time mode change between controllers without a torque step (docs/control.md).

#include <array>

#include "teleop/control/controllers.h"
#include "teleop/control/types.h"

namespace teleop::control {

/// Holds up to kMaxModes controllers (not owned) and runs one of them. select() starts a
/// linear torque blend of blend_s from the old controller's output to the new one's:
///   tau_k = (1 - a_k) (tau_old,k + delta) + a_k tau_new,k,   a_k = min(1, k cycle_s / blend_s)
/// both controllers being evaluated at every cycle of the blend (delta = 0, see select()).
/// Per joint, the change from one cycle to the next is then bounded by
///   |tau_k - tau_k-1| <= max(|dtau_old,k|, |dtau_new,k|) + (cycle_s / blend_s) |tau_new,k-1 - tau_old,k-1 - delta|
/// i.e. the controllers' own per-cycle changes plus the gap between them spread over
/// blend_s / cycle_s cycles (50 cycles by default) instead of a step of the whole gap.
/// compute() and select() do not allocate.
class ControllerSwitch {
 public:
  static constexpr int kMaxModes = 8;

  ControllerSwitch(double cycle_s, double blend_s = 0.05);

  /// Adds a mode (setup time); returns its index. The first one added is active. Throws
  /// std::length_error beyond kMaxModes.
  int add(Controller& controller);

  /// Switches to `mode` from the next compute() on (out-of-range or current target: ignored).
  /// Before the first compute() the switch is immediate: no torque has been output yet.
  /// During a blend, the blend restarts from the mode being blended to, carrying the difference
  /// between the last output and that mode's torque as the offset delta (fading with 1 - a),
  /// so a second switch is bumpless too.
  void select(int mode);

  JointVector compute(const ArmState& state, const ArmCommand& command);

  /// The mode that runs (or is being blended to).
  int mode() const { return to_; }
  bool blending() const { return from_ != to_; }
  /// The mode being blended from (== mode() when not blending).
  int from_mode() const { return from_; }
  /// a of the last compute() (1 when not blending).
  double blend_weight() const { return alpha_; }
  Controller& controller(int mode) const { return *modes_[static_cast<std::size_t>(mode)]; }

 private:
  double step_;  ///< cycle_s / blend_s
  std::array<Controller*, kMaxModes> modes_{};
  int count_ = 0;
  int from_ = 0;
  int to_ = 0;
  double alpha_ = 1.0;
  bool have_output_ = false;
  bool need_offset_ = false;
  JointVector offset_ = JointVector::Zero();
  JointVector last_ = JointVector::Zero();
};

}  // namespace teleop::control
