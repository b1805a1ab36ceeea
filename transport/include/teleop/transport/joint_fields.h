#pragma once
// Copies between fixed-size joint vectors and the bounded sequences of the samples, and between
// plain arrays and the samples' vectors and quaternions.

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

/// Three numbers (x, y, z) into a Vector3, and back.
inline void set_vector3(msg::Vector3& out, const double* xyz) {
  out.x(xyz[0]);
  out.y(xyz[1]);
  out.z(xyz[2]);
}
inline void read_vector3(const msg::Vector3& in, double* xyz) {
  xyz[0] = in.x();
  xyz[1] = in.y();
  xyz[2] = in.z();
}

/// Four numbers (w, x, y, z) into a Quaternion, and back.
inline void set_quaternion(msg::Quaternion& out, const double* wxyz) {
  out.w(wxyz[0]);
  out.x(wxyz[1]);
  out.y(wxyz[2]);
  out.z(wxyz[3]);
}
inline void read_quaternion(const msg::Quaternion& in, double* wxyz) {
  wxyz[0] = in.w();
  wxyz[1] = in.x();
  wxyz[2] = in.y();
  wxyz[3] = in.z();
}

/// Writes a force [N] and a moment [N m] (x, y, z each) into a WrenchStamped.
inline void set_wrench(msg::WrenchStamped& out, const double* force_n, const double* torque_nm) {
  set_vector3(out.force_n(), force_n);
  set_vector3(out.torque_nm(), torque_nm);
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
