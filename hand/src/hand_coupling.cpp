#include "teleop/hand/hand_coupling.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::hand {

// clang-format off
const std::array<std::string_view, kHandJoints> kHandJointNames = {
    "Thumb_Flexion",          // 0  motor 0
    "j3",                     // 1  motor 0, thumb middle
    "j4",                     // 2  motor 0, thumb distal
    "Thumb_Opposition",       // 3  motor 1
    "j5",                     // 4  motor 1, palm
    "Index_Finger_Distal",    // 5  motor 2
    "j14",                    // 6  motor 2, index tip
    "Index_Finger_Proximal",  // 7  motor 3
    "Middle_Finger_Distal",   // 8  motor 4
    "j15",                    // 9  motor 4, middle tip
    "Middle_Finger_Proximal", // 10 motor 5
    "Ring_Finger",            // 11 motor 6
    "j12",                    // 12 motor 6, ring middle
    "j16",                    // 13 motor 6, ring tip
    "Pinky",                  // 14 motor 7
    "j13",                    // 15 motor 7, pinky middle
    "j17",                    // 16 motor 7, pinky tip
    "Finger_Spread",          // 17 motor 8, the pinky's spread
    "index_spread",           // 18 motor 8
    "ring_spread",            // 19 motor 8
};
// clang-format on

const std::array<std::string_view, kHandMotors> kHandMotorNames = {
    "Thumb_Flexion",        "Thumb_Opposition",       "Index_Finger_Distal", "Index_Finger_Proximal",
    "Middle_Finger_Distal", "Middle_Finger_Proximal", "Ring_Finger",         "Pinky",
    "Finger_Spread",
};

HandCoupling HandCoupling::svh() {
  // clang-format off
  // <mimic> multipliers of the SVH URDF; the middle finger has no spread joint (fixed)
  const std::array<CouplingTerm, kHandJoints> terms = {{
      {0, 1.0}, {0, 1.01511}, {0, 1.44889},  // thumb flexion: Thumb_Flexion, j3, j4
      {1, 1.0}, {1, 1.0},                    // thumb opposition: Thumb_Opposition, j5
      {2, 1.0}, {2, 1.045},                  // index distal: Index_Finger_Distal, j14
      {3, 1.0},                              // index proximal
      {4, 1.0}, {4, 1.0454},                 // middle distal: Middle_Finger_Distal, j15
      {5, 1.0},                              // middle proximal
      {6, 1.0}, {6, 1.3588}, {6, 1.42093},   // ring: Ring_Finger, j12, j16
      {7, 1.0}, {7, 1.3588}, {7, 1.42307},   // pinky: Pinky, j13, j17
      {8, 1.0}, {8, 0.5}, {8, 0.5},          // spread: Finger_Spread, index_spread, ring_spread
  }};
  // clang-format on
  return HandCoupling(terms, HandJointVector{});
}

HandCoupling::HandCoupling(const std::array<CouplingTerm, kHandJoints>& terms, const HandJointVector& q0_rad)
    : terms_(terms), q0_(q0_rad) {
  for (size_t j = 0; j < kHandJoints; ++j) {
    const CouplingTerm& t = terms_[j];
    if (t.motor >= kHandMotors) {
      throw std::invalid_argument("HandCoupling: joint " + std::to_string(j) + " names motor " +
                                  std::to_string(t.motor) + ", the hand has 9");
    }
    if (!std::isfinite(t.factor) || t.factor == 0.0) {
      throw std::invalid_argument("HandCoupling: joint " + std::to_string(j) + " has a zero or non-finite factor");
    }
    if (!std::isfinite(q0_[j])) throw std::invalid_argument("HandCoupling: joint " + std::to_string(j) + " offset");
    column_norm2_[t.motor] += t.factor * t.factor;
  }
  for (size_t k = 0; k < kHandMotors; ++k) {
    if (column_norm2_[k] == 0.0) {
      throw std::invalid_argument("HandCoupling: motor " + std::to_string(k) + " drives no joint");
    }
  }
}

HandJointVector HandCoupling::joints_from_motors(const HandMotorVector& m_rad) const {
  HandJointVector q;
  for (size_t j = 0; j < kHandJoints; ++j) q[j] = terms_[j].factor * m_rad[terms_[j].motor] + q0_[j];
  return q;
}

HandMotorVector HandCoupling::motors_from_joints(const HandJointVector& q_rad) const {
  HandMotorVector m{};
  for (size_t j = 0; j < kHandJoints; ++j) m[terms_[j].motor] += terms_[j].factor * (q_rad[j] - q0_[j]);
  for (size_t k = 0; k < kHandMotors; ++k) m[k] /= column_norm2_[k];
  return m;
}

double HandCoupling::coefficient(size_t joint, size_t motor) const {
  if (joint >= kHandJoints || motor >= kHandMotors) return 0.0;
  return terms_[joint].motor == motor ? terms_[joint].factor : 0.0;
}

}  // namespace teleop::hand
