#pragma once
// Model-mediated teleoperation's model update (issue 6, docs/architectures.md "MMT: the follower
// corrects the twin"): where an environment surface of the twin (the stiff wall) really is, along
// its outward normal, estimated from the follower's measurements, and the offset the twin applies
// to its geom, moved towards the estimate rate-limited and bounded so that the operator never
// feels a jump. Pure arithmetic on one axis: what a measurement means geometrically is the
// caller's (RemoteContactProbe). Real-time safe: nothing allocates, nothing throws.
//
// Offsets are along the outward normal n (from the surface towards the robot), relative to the
// surface of the model as loaded: +1 cm moves the surface 1 cm towards the robot.

#include <array>
#include <cstdint>
#include <string>

namespace teleop::twin {

/// `twin.mmt.correction` (absent: no correction).
struct CorrectionConfig {
  /// The twin's environment geom that is moved.
  std::string geom = "wall";
  /// The follower's geometry that touches it: "geom:NAME" or "body:NAME" (its colliding geoms).
  std::string probe = "body:link7";
  /// Outward surface normal in the world frame (unit length after parsing).
  std::array<double, 3> normal{-1.0, 0.0, 0.0};
  /// The follower is in contact when the environment pushes it along n with at least this force.
  double contact_force_n = 6.0;
  /// ... and free of it below this one (between the two: no information, the momentum
  /// observer's lag and noise at the edge of contact).
  double free_force_n = 4.0;
  /// A free follower whose probe is more than this behind the estimated surface: the real surface
  /// is taken to be this much behind the probe (less: within tolerance, nothing learnt).
  double free_margin_m = 0.001;
  /// Largest speed of the applied offset [m/s].
  double rate_m_per_s = 0.02;
  /// Largest |estimate| and |applied offset| [m].
  double max_offset_m = 0.05;
  /// Measurements older than this (source stamp to now) are ignored.
  double timeout_s = 0.1;
  /// The joint state and the wrench of one measurement: their stamps at most this far apart.
  double max_skew_s = 0.005;
};

/// One measurement of the follower, in the geometry of the twin's model.
struct SurfaceMeasurement {
  /// Signed distance of the follower's probe (at its measured pose) from the twin's surface as
  /// it is now [m]; negative: the probe is behind it.
  double gap_m = 0.0;
  /// Force the environment exerts on the follower along n [N].
  double normal_force_n = 0.0;
  /// Age of the older of its two samples [s].
  double age_s = 0.0;
};

class EnvironmentCorrection {
 public:
  explicit EnvironmentCorrection(const CorrectionConfig& config) : config_(config) {}

  enum class Outcome {
    kContact,    ///< in contact: the real surface is at the probe
    kFree,       ///< free, but the twin's surface would touch: the real one is further back
    kNoChange,   ///< consistent with the estimate (or between the force thresholds)
    kStale,      ///< older than the timeout: ignored
    kNonFinite,  ///< NaN/Inf: ignored
  };

  /// Updates the estimate from one measurement (taken against the surface at applied_m()).
  [[nodiscard]] Outcome measure(const SurfaceMeasurement& m);
  /// Moves the applied offset towards the estimate by at most rate * dt_s; returns it.
  double advance(double dt_s);

  /// Where the real surface is believed to be [m along n].
  double estimate_m() const { return estimate_m_; }
  /// The offset the twin's surface has now [m along n].
  double applied_m() const { return applied_m_; }

  uint64_t contact_updates() const { return contact_updates_; }
  uint64_t free_updates() const { return free_updates_; }
  uint64_t stale() const { return stale_; }
  uint64_t non_finite() const { return non_finite_; }
  /// Estimates cut at max_offset_m.
  uint64_t clamped() const { return clamped_; }

 private:
  void set_estimate(double offset_m);

  CorrectionConfig config_;
  double estimate_m_ = 0.0;
  double applied_m_ = 0.0;
  uint64_t contact_updates_ = 0;
  uint64_t free_updates_ = 0;
  uint64_t stale_ = 0;
  uint64_t non_finite_ = 0;
  uint64_t clamped_ = 0;
};

}  // namespace teleop::twin
