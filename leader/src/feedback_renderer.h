#pragma once
// What the operator feels: the architecture's raw feedback torque, scaled (gain), smoothed
// (first-order low-pass), faded in and out (source lost or clutch pressed: to zero over fade_s,
// never a step), rate limited and saturated per joint. Every clipping is counted.

#include <cstdint>

#include "teleop/common/joint_model.h"
#include "teleop/common/lowpass.h"

namespace teleop::leader {

struct FeedbackConfig {
  double gain = 1.0;
  double cutoff_hz = 30.0;
  /// Per joint, what the device may render [Nm].
  JointVector max_torque_nm = [] {
    JointVector v{};
    v.fill(20.0);
    return v;
  }();
  /// Largest change per second of the rendered torque (infinite or 0: none; `off` in YAML).
  double max_rate_nm_per_s = 500.0;
  /// Time to fade the feedback to zero (source lost, clutch) and back.
  double fade_s = 0.2;
  /// Time to fade it out once the operator let go (the dead-man released, hands_off_guard.h):
  /// short, as nothing but the device's own friction opposes the force then.
  double hands_off_fade_s = 0.02;
};

class FeedbackRenderer {
 public:
  FeedbackRenderer(size_t joints, const FeedbackConfig& config, double rate_hz);

  /// One cycle: `raw` is the architecture's feedback; `active` false (source lost or stale,
  /// clutch engaged) fades the output to zero, within hands_off_fade_s when `let_go`. Real-time safe.
  const JointVector& render(const JointVector& raw, bool active, bool let_go = false);

  const JointVector& output() const { return out_; }
  /// 1: full feedback, 0: faded out.
  double fade() const { return fade_; }
  uint64_t saturations() const { return saturations_; }
  uint64_t rate_limited() const { return rate_limited_; }
  double peak_nm() const { return peak_nm_; }

 private:
  size_t joints_;
  FeedbackConfig config_;
  LowPassFilter filter_;
  double fade_step_;
  double let_go_step_;
  double rate_step_;
  double fade_ = 0.0;  // starts faded out: feedback comes in gently
  JointVector out_{};
  uint64_t saturations_ = 0;
  uint64_t rate_limited_ = 0;
  double peak_nm_ = 0.0;
};

}  // namespace teleop::leader
