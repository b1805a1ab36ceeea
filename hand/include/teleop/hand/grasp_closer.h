#pragma once
// A grasp by feel, as a hand's master can run it on the feedback it has (motor angles, no
// tactile sensing): the thumb is first turned into opposition, then every closing finger's
// target advances at a constant speed until the finger stops following it (it lags the target
// by more than `contact_lag_rad`: something holds it), and from then on the target stays a
// fixed squeeze past where the finger stopped, so the drive presses with a bounded position
// error (the drives' following error window, 0x6065, is 0.2 rad: the squeeze must stay below
// it). A finger that meets nothing stops at its closed angle. Used by the grasp tests (in
// process and over vcan); plain arithmetic, real-time safe.

#include <array>

#include "teleop/hand/hand_coupling.h"

namespace teleop::hand {

struct GraspCloserConfig {
  /// Angles the fingers close to when they meet nothing [rad] (SVH motor order).
  HandMotorVector closed_rad{};
  /// Motors that close by feel; the others go straight to closed_rad (e.g. the opposition and
  /// the spread, which set the hand's shape).
  std::array<bool, kHandMotors> by_feel{};
  /// Time the shaping motors get before the others start [s].
  double shape_time_s = 0.6;
  double closing_speed_radps = 0.5;
  /// A finger lagging its target by more than this has met something.
  double contact_lag_rad = 0.08;
  /// Target past the contact angle once a finger has met something.
  double squeeze_rad = 0.12;
};

class GraspCloser {
 public:
  explicit GraspCloser(const GraspCloserConfig& config) : config_(config) {}

  /// Starts closing from the motor angles `from_rad`.
  void start(const HandMotorVector& from_rad);
  /// The targets at time t_s since start, from the motor angles measured now. Real-time safe.
  const HandMotorVector& update(double t_s, const HandMotorVector& measured_rad);

  /// True once motor k met something (its target is then the contact angle + squeeze).
  bool in_contact(size_t k) const { return contact_[k]; }
  /// The angle at which motor k met something [rad].
  double contact_rad(size_t k) const { return contact_rad_[k]; }
  const HandMotorVector& targets() const { return target_; }

 private:
  GraspCloserConfig config_;
  HandMotorVector from_{};
  HandMotorVector target_{};
  HandMotorVector contact_rad_{};
  std::array<bool, kHandMotors> contact_{};
  double last_t_s_ = 0.0;
};

}  // namespace teleop::hand
