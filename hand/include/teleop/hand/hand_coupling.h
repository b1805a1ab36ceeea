#pragma once
// The mechanical coupling of the 9-motor, 20-joint SVH-class hand: q = S_m m + q0 (SVH paper,
// eq. 1). In this hand every joint is driven by exactly one motor, so S_m (20 x 9) is stored
// sparsely as one (motor, factor) term per joint.
//
// Default values (HandCoupling::svh()): the SVH paper gives the structure but no numbers; the
// factors are the <mimic> multipliers of the SCHUNK SVH URDF (schunk_svh_description), whose
// offsets are all 0, so q0 = 0. Joint names are the URDF's, without the hand prefix.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace teleop::hand {

constexpr size_t kHandMotors = 9;
constexpr size_t kHandJoints = 20;
using HandMotorVector = std::array<double, kHandMotors>;
using HandJointVector = std::array<double, kHandJoints>;

/// Motor (channel) order of the SVH, as in idl/hand.idl.
namespace hand_motor {
constexpr size_t kThumbFlexion = 0;
constexpr size_t kThumbOpposition = 1;
constexpr size_t kIndexDistal = 2;
constexpr size_t kIndexProximal = 3;
constexpr size_t kMiddleDistal = 4;
constexpr size_t kMiddleProximal = 5;
constexpr size_t kRing = 6;
constexpr size_t kPinky = 7;
constexpr size_t kFingerSpread = 8;
}  // namespace hand_motor

/// The 20 joints in the order of HandJointVector: each motor's main joint followed by the
/// joints it drives through the mechanism.
extern const std::array<std::string_view, kHandJoints> kHandJointNames;
extern const std::array<std::string_view, kHandMotors> kHandMotorNames;

/// One non-zero of S_m: joint j = factor * motor.
struct CouplingTerm {
  uint8_t motor = 0;
  double factor = 0.0;
};

class HandCoupling {
 public:
  /// The SVH defaults (see the file comment and docs/can_bus_budget.md).
  static HandCoupling svh();

  /// Throws std::invalid_argument for a motor index >= 9, a non-finite or zero factor, a
  /// non-finite offset, or a motor that drives no joint.
  HandCoupling(const std::array<CouplingTerm, kHandJoints>& terms, const HandJointVector& q0_rad);

  /// q = S_m m + q0. Real-time safe.
  HandJointVector joints_from_motors(const HandMotorVector& m_rad) const;
  /// The least-squares motor vector for joint angles: m_k = sum_j s_jk (q_j - q0_j) / sum_j s_jk^2.
  /// For q in the range of S_m it inverts joints_from_motors exactly. Real-time safe.
  HandMotorVector motors_from_joints(const HandJointVector& q_rad) const;

  /// Entry (joint, motor) of the dense S_m.
  double coefficient(size_t joint, size_t motor) const;
  const std::array<CouplingTerm, kHandJoints>& terms() const { return terms_; }
  const HandJointVector& offsets() const { return q0_; }

 private:
  std::array<CouplingTerm, kHandJoints> terms_;
  HandJointVector q0_;
  HandMotorVector column_norm2_{};  // sum_j s_jk^2 per motor
};

}  // namespace teleop::hand
