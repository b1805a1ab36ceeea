#include "feedback_renderer.h"

#include <algorithm>
#include <cmath>

namespace teleop::leader {

FeedbackRenderer::FeedbackRenderer(size_t joints, const FeedbackConfig& config, double rate_hz)
    : joints_(joints),
      config_(config),
      filter_(config.cutoff_hz, rate_hz),
      fade_step_(config.fade_s > 0 ? 1.0 / (config.fade_s * rate_hz) : 1.0),
      let_go_step_(std::max(fade_step_, config.hands_off_fade_s > 0 ? 1.0 / (config.hands_off_fade_s * rate_hz) : 1.0)),
      rate_step_(config.max_rate_nm_per_s > 0 ? config.max_rate_nm_per_s / rate_hz : 0.0) {}

const JointVector& FeedbackRenderer::render(const JointVector& raw, bool active, bool let_go) {
  fade_ = std::clamp(fade_ + (active ? fade_step_ : -(let_go ? let_go_step_ : fade_step_)), 0.0, 1.0);
  // the filter runs on the raw signal all the time, so fading back in starts from its present value
  const JointVector& smooth = filter_.apply(raw, joints_);
  for (size_t i = 0; i < joints_; ++i) {
    double t = fade_ * config_.gain * smooth[i];
    if (rate_step_ > 0) {
      const double limited = std::clamp(t, out_[i] - rate_step_, out_[i] + rate_step_);
      if (limited != t) ++rate_limited_;
      t = limited;
    }
    const double saturated = std::clamp(t, -config_.max_torque_nm[i], config_.max_torque_nm[i]);
    if (saturated != t) ++saturations_;
    out_[i] = saturated;
    peak_nm_ = std::max(peak_nm_, std::abs(saturated));
  }
  return out_;
}

}  // namespace teleop::leader
