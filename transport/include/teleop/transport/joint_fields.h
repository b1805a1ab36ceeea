#pragma once
// Copies between fixed-size joint vectors and the bounded sequences of the samples.

#include <algorithm>
#include <cstddef>
#include <vector>

#include <teleop/msg/arm.h>

#include "teleop/common/joint_model.h"

namespace teleop::transport {

/// Writes the first n values into `out` (resized to n; no allocation once its capacity is n).
inline void copy_joints(const JointVector& in, size_t n, std::vector<double>& out) {
  out.resize(n);
  std::copy_n(in.begin(), n, out.begin());
}

/// Reads a sequence into a joint vector. Returns false when its length is not n.
[[nodiscard]] inline bool read_joints(const std::vector<double>& in, size_t n, JointVector& out) {
  if (in.size() != n || n > out.size()) return false;
  std::copy_n(in.begin(), n, out.begin());
  return true;
}

/// Writes a force [N] and a moment [N m] (x, y, z each) into a WrenchStamped.
inline void set_wrench(msg::WrenchStamped& out, const double* force_n, const double* torque_nm) {
  out.force_n().x(force_n[0]);
  out.force_n().y(force_n[1]);
  out.force_n().z(force_n[2]);
  out.torque_nm().x(torque_nm[0]);
  out.torque_nm().y(torque_nm[1]);
  out.torque_nm().z(torque_nm[2]);
}

/// Sizes every sequence of a sample once at setup so that the loop never allocates.
template <typename... Seq>
void presize(size_t n, Seq&... sequences) {
  (sequences.resize(n), ...);
}

/// Sizes the four joint sequences of a JointState to n joints (setup time).
inline void presize_joint_state(msg::JointState& state, size_t n) {
  presize(n, state.q_rad(), state.dq_radps(), state.tau_measured_nm(), state.tau_ext_nm());
}

}  // namespace teleop::transport
