#pragma once
// Model-mediated teleoperation's object update (issue 6, docs/twin.md "Object correction"): the
// remote site measures a loose object (the box task's box) and the twin pulls its copy of it
// towards the measurement with a bounded spring-damper wrench, so that a box that slipped in the
// follower's hands, or was knocked, slips in the twin's too and the operator feels it. A pull,
// not a jump: the twin's contacts stay consistent and the operator's hands never feel a step.
//
// The measurement is one network delay old; its position is carried forward over its age with its
// measured velocity before the spring compares (a box carried at 0.2 m/s under a 17 ms delay
// would otherwise be pulled 3.5 mm back). Pure arithmetic, real-time safe: nothing allocates or
// throws after construction.

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "teleop/sim/body_state.h"

namespace teleop::twin {

/// `twin.object_correction` (absent: the twin's objects follow only the twin's own physics).
struct ObjectCorrectionConfig {
  /// Bodies of the twin's model measured at the remote site (teleop/follower/object_pose/<body>).
  std::vector<std::string> bodies;
  double stiffness_n_per_m = 200.0;
  double damping_ns_per_m = 30.0;
  double stiffness_nm_per_rad = 2.0;
  double damping_nms_per_rad = 0.3;
  /// Bounds of the pull: less than the object's weight, so the twin's hands still carry it.
  double max_force_n = 8.0;
  double max_torque_nm = 1.0;
  /// A measurement older than this (source stamp to now) no longer pulls.
  double timeout_s = 0.1;
};

/// A force and a moment in the world frame, applied at the body's centre of mass.
struct CorrectionWrench {
  std::array<double, 3> force_n{};
  std::array<double, 3> torque_nm{};
};

class ObjectCorrection {
 public:
  explicit ObjectCorrection(const ObjectCorrectionConfig& config) : config_(config) {}

  enum class Outcome {
    kAccepted,   ///< the new target
    kStale,      ///< older than the timeout on arrival: ignored
    kNonFinite,  ///< NaN/Inf anywhere, or not a unit quaternion: ignored
  };

  /// Takes one measurement of the remote object, `age_s` old when it arrived at `now_s` (any
  /// monotonic time base, the same as wrench()'s).
  [[nodiscard]] Outcome measure(const sim::BodyState& measured, double age_s, double now_s);

  /// The wrench on the twin's object in state `twin` at `now_s`: zero without a measurement
  /// younger than the timeout. Bounded by max_force_n / max_torque_nm (counted when cut).
  CorrectionWrench wrench(const sim::BodyState& twin, double now_s);

  /// The measured position carried forward to `now_s` (valid once a measurement was accepted).
  std::array<double, 3> predicted_position_m(double now_s) const;
  /// |predicted - twin| of the last wrench() [m]; NaN while nothing pulls.
  double position_error_m() const { return position_error_m_; }
  /// |force| of the last wrench() [N].
  double force_n() const { return force_n_; }

  uint64_t accepted() const { return accepted_; }
  uint64_t stale() const { return stale_; }
  uint64_t non_finite() const { return non_finite_; }
  /// wrench() calls whose force or moment was cut at its bound.
  uint64_t clamped() const { return clamped_; }

 private:
  double age_at(double now_s) const { return measured_age_s_ + (now_s - measured_at_s_); }

  ObjectCorrectionConfig config_;
  bool has_target_ = false;
  sim::BodyState target_;
  double measured_age_s_ = 0.0;
  double measured_at_s_ = 0.0;
  double position_error_m_ = std::numeric_limits<double>::quiet_NaN();
  double force_n_ = 0.0;
  uint64_t accepted_ = 0;
  uint64_t stale_ = 0;
  uint64_t non_finite_ = 0;
  uint64_t clamped_ = 0;
};

}  // namespace teleop::twin
