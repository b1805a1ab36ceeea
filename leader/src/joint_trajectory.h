#pragma once
// A recorded joint trajectory: positions (and velocities) against time, loaded once from a CSV
// file and then sampled in the loop by linear interpolation without allocating. The leader's
// trace (columns t_s, ..., q_dev_0..) is a valid input with q_prefix "q_dev_", so a recorded
// run can be replayed.

#include <cstddef>
#include <string>
#include <vector>

#include "teleop/common/joint_model.h"

namespace teleop::leader {

/// Columns of the torque the operator's hand adds on purpose (e.g. squeezing an object), per joint.
inline constexpr const char* kOperatorTorquePrefix = "tau_op_";

class JointTrajectory {
 public:
  /// Loads `path`: a header row, then one row per sample. Columns: `t_s` (time [s], strictly
  /// increasing, taken relative to the first row), `<q_prefix>0 .. <q_prefix>{joints-1}`
  /// (positions [rad]) and optionally `d<q_prefix>0 ..` (velocities [rad/s]; when absent they
  /// are computed by finite differences) and `tau_op_0 ..` (the operator's intended torque [Nm],
  /// zero when absent). Other columns are ignored.
  /// Configuration time: throws ConfigError "<file>:<line>: <column>: <problem>" for a missing
  /// file or column, a field that is not a number, NaN/Inf, a time not after the previous row's,
  /// or fewer than 2 rows.
  static JointTrajectory load_csv(const std::string& path, size_t joints, const std::string& q_prefix = "q_");

  /// Wrap around at the end instead of holding the last row (time taken modulo duration_s()).
  void set_loop(bool loop) { loop_ = loop; }
  bool loop() const { return loop_; }

  /// The trajectory at `t_s` after its first row, linearly interpolated. Before the start the
  /// first row is held, after the end the last row (or, looping, the time wraps); a held
  /// position has dq = 0. Only the first joints() entries are written. Real-time safe.
  void sample(double t_s, JointVector& q_rad, JointVector& dq_radps) const;

  /// The operator's intended torque at `t_s` (zero without tau_op_ columns), interpolated like the
  /// positions; before the start and after the end the first or last row's is held. Real-time safe.
  void sample_torque(double t_s, JointVector& tau_nm) const;

  size_t joints() const { return joints_; }
  size_t rows() const { return t_s_.size(); }
  /// Time of the last row relative to the first [s].
  double duration_s() const { return t_s_.back(); }

 private:
  // where t_s falls: in [t_row, t_row+1) at `weight`, or `held` at row (before the start, after the end)
  struct Segment {
    size_t row;
    double weight;
    bool held;
  };
  JointTrajectory(size_t joints, std::vector<double> t_s, std::vector<double> q, std::vector<double> dq,
                  std::vector<double> tau);
  Segment locate(double t_s) const;
  void hold(size_t row, JointVector& q_rad, JointVector& dq_radps) const;

  size_t joints_;
  std::vector<double> t_s_;  // per row, relative to the first
  std::vector<double> q_;    // row-major, rows() x joints_
  std::vector<double> dq_;   // row-major, rows() x joints_
  std::vector<double> tau_;  // row-major, rows() x joints_; empty without tau_op_ columns
  bool loop_ = false;
};

}  // namespace teleop::leader
