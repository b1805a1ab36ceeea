#include "object_correction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::twin {
namespace {

using Vector3 = Eigen::Vector3d;

Vector3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
Eigen::Quaterniond quat(const std::array<double, 4>& q) { return {q[0], q[1], q[2], q[3]}; }

bool all_finite(const std::array<double, 3>& a) {
  return std::all_of(a.begin(), a.end(), [](double v) { return std::isfinite(v); });
}

bool finite(const sim::BodyState& s) {
  if (!all_finite(s.position_m) || !all_finite(s.linear_mps) || !all_finite(s.angular_radps)) return false;
  const double norm = quat(s.orientation_wxyz).norm();
  // a tracker's quaternion is unit to its float precision; anything else is not an orientation
  return std::isfinite(norm) && std::abs(norm - 1.0) < 1e-3;
}

// the rotation vector taking `from` to `to` (world frame), the short way round
Vector3 rotation_error(const Eigen::Quaterniond& to, const Eigen::Quaterniond& from) {
  Eigen::Quaterniond delta = to.normalized() * from.normalized().conjugate();
  if (delta.w() < 0.0) delta.coeffs() = -delta.coeffs();
  const Eigen::AngleAxisd turn(delta);
  return turn.angle() * turn.axis();
}

// scales `v` down to `bound` when longer; true when it did
bool clamp_norm(Vector3& v, double bound) {
  const double n = v.norm();
  if (n <= bound) return false;
  v *= bound / n;
  return true;
}

}  // namespace

ObjectCorrection::Outcome ObjectCorrection::measure(const sim::BodyState& measured, double age_s, double now_s) {
  if (!finite(measured) || !std::isfinite(age_s) || !std::isfinite(now_s)) {
    ++non_finite_;
    return Outcome::kNonFinite;
  }
  if (age_s > config_.timeout_s) {
    ++stale_;
    return Outcome::kStale;
  }
  target_ = measured;
  // a clock skew between the sites can make a sample look younger than nothing: it is new
  measured_age_s_ = std::max(age_s, 0.0);
  measured_at_s_ = now_s;
  has_target_ = true;
  ++accepted_;
  return Outcome::kAccepted;
}

std::array<double, 3> ObjectCorrection::predicted_position_m(double now_s) const {
  const Vector3 p = vec(target_.position_m) + age_at(now_s) * vec(target_.linear_mps);
  return {p.x(), p.y(), p.z()};
}

CorrectionWrench ObjectCorrection::wrench(const sim::BodyState& twin, double now_s) {
  CorrectionWrench w;
  if (!has_target_ || age_at(now_s) > config_.timeout_s) {
    // the remote site went quiet: the twin's own physics is all there is
    position_error_m_ = std::numeric_limits<double>::quiet_NaN();
    force_n_ = 0.0;
    return w;
  }
  const Vector3 position_error = vec(predicted_position_m(now_s)) - vec(twin.position_m);
  Vector3 force = config_.stiffness_n_per_m * position_error +
                  config_.damping_ns_per_m * (vec(target_.linear_mps) - vec(twin.linear_mps));
  Vector3 torque =
      config_.stiffness_nm_per_rad * rotation_error(quat(target_.orientation_wxyz), quat(twin.orientation_wxyz)) +
      config_.damping_nms_per_rad * (vec(target_.angular_radps) - vec(twin.angular_radps));
  const bool cut_force = clamp_norm(force, config_.max_force_n);
  const bool cut_torque = clamp_norm(torque, config_.max_torque_nm);
  if (cut_force || cut_torque) ++clamped_;
  for (int k = 0; k < 3; ++k) {
    w.force_n[k] = force[k];
    w.torque_nm[k] = torque[k];
  }
  position_error_m_ = position_error.norm();
  force_n_ = force.norm();
  return w;
}

}  // namespace teleop::twin
