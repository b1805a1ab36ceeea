#include "model_correction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "teleop/common/clock.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/topics.h"

namespace teleop::twin {
namespace {

// the narrow phase looks this far: beyond any offset the correction may apply
double gap_range_m(const CorrectionConfig& c) { return 2.0 * c.max_offset_m + 0.1; }

bool all_finite(const JointVector& q, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(q[i])) return false;
  }
  return true;
}

}  // namespace

ModelCorrection::ModelCorrection(const CorrectionConfig& config, const TwinSimulation& sim,
                                 transport::Participant& participant)
    : config_(config),
      probe_(sim.simulation().model(), config.probe, config.geom, sim.config().model_path),
      correction_(config),
      state_(participant, transport::topics::kFollowerState),
      wrench_(participant, transport::topics::kFollowerWrench) {
  // where the geom is in the model as loaded (geom_offsets included): offsets are from there
  const mjtNum* pos = sim.simulation().model()->geom_pos + 3 * probe_.geom();
  for (size_t k = 0; k < 3; ++k) base_pos_m_[k] = pos[k];
}

void ModelCorrection::cycle(TwinSimulation& sim, double dt_s) {
  const bool new_state = state_.poll() > 0;
  wrench_.poll();
  if (new_state && wrench_.has_sample()) measure(sim);
  const double offset_m = correction_.advance(dt_s);
  std::array<double, 3> pos;
  for (size_t k = 0; k < 3; ++k) pos[k] = base_pos_m_[k] + offset_m * config_.normal[k];
  sim.set_geom_position(probe_.geom(), pos);
}

void ModelCorrection::measure(const TwinSimulation& sim) {
  const msg::JointState& state = state_.latest();
  const msg::WrenchStamped& wrench = wrench_.latest();
  const int64_t state_ns = state.header().stamp_ns();
  const int64_t wrench_ns = wrench.header().stamp_ns();
  // the pose and the force of one follower cycle (the other one of the pair lost or late: wait)
  if (std::abs(static_cast<double>(state_ns - wrench_ns)) * 1e-9 > config_.max_skew_s) {
    ++unpaired_;
    return;
  }
  SurfaceMeasurement m;
  m.age_s = static_cast<double>(system_now_ns() - std::min(state_ns, wrench_ns)) * 1e-9;
  // the wrench acts on the follower, in its base frame, which is the twin's world
  const auto& f = wrench.force_n();
  m.normal_force_n = f.x() * config_.normal[0] + f.y() * config_.normal[1] + f.z() * config_.normal[2];
  const size_t n = sim.joints();
  if (transport::read_joints(state.q_rad(), n, q_) && all_finite(q_, n)) {
    m.gap_m = probe_.gap_m(sim.simulation().model(), q_, gap_range_m(config_));
  } else {
    // a wrong joint count is as unusable as a NaN: the correction ignores and counts it
    ++malformed_;
    m.gap_m = std::numeric_limits<double>::quiet_NaN();
  }
  last_gap_m_ = m.gap_m;
  last_force_n_ = m.normal_force_n;
  (void)correction_.measure(m);
}

void ModelCorrection::fill_report(runtime::NodeReport& report) const {
  report.add(state_);
  report.add(wrench_);
  report.counters.emplace_back("env_offset_m", correction_.applied_m());
  report.counters.emplace_back("env_estimate_m", correction_.estimate_m());
  report.counters.emplace_back("correction_contact_updates", static_cast<double>(correction_.contact_updates()));
  report.counters.emplace_back("correction_free_updates", static_cast<double>(correction_.free_updates()));
  report.counters.emplace_back("correction_stale", static_cast<double>(correction_.stale()));
  report.counters.emplace_back("correction_rejected", static_cast<double>(correction_.non_finite()));
  report.counters.emplace_back("correction_malformed", static_cast<double>(malformed_));
  report.counters.emplace_back("correction_unpaired", static_cast<double>(unpaired_));
  report.counters.emplace_back("correction_clamped", static_cast<double>(correction_.clamped()));
}

void ModelCorrection::trace_columns(std::vector<std::string>& columns) const {
  for (const char* c : {"env_offset_m", "env_estimate_m", "follower_gap_m", "follower_normal_force_n"}) {
    columns.emplace_back(c);
  }
}

double* ModelCorrection::trace_row(double* row) const {
  *row++ = correction_.applied_m();
  *row++ = correction_.estimate_m();
  *row++ = last_gap_m_;
  *row++ = last_force_n_;
  return row;
}

}  // namespace teleop::twin
