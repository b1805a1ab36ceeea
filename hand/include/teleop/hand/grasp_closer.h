#pragma once
// A grasp by feel, as a hand's master can run it on the feedback it has (motor angles, no
// tactile sensing): the thumb is first turned into opposition, then every closing finger's
// target advances at a constant speed until the finger stops following it (it lags the target
// by more than `contact_lag_rad`: something holds it), and from then on the target stays a
// fixed squeeze past where the finger stopped, so the drive presses with a bounded position
// error (the drives' following error window, 0x6065, is 0.2 rad: the squeeze must stay below
// it) and a current within the grasp's limit. A finger that meets nothing stops at its closed
// angle. (Following the object as it gives way, the target a squeeze past the finger at every
// update, was tried: the four fingers then push the thumb open until it faults.) Used by the grasp tests (in
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
  /// Current limit of each motor during the grasp [A] (0: the adapter's default).
  HandMotorVector current_limit_a{};
};

/// The power grasp of the MuJoCo hand's grasp scene (config/models/svh_hand_grasp.xml,
/// docs/hand.md), with `closed_rad` the motors' upper limits: the thumb turned into opposition
/// (0.9 rad) and the spread closed (0), then the thumb's flexion and the four fingers by feel,
/// squeezing 0.04 rad past contact; the fingers at 1.0 A (0.8 N m), the thumb at 1.5 A. (With
/// the fingers at 0.6 or 0.8 A the tube slides along its axis out of the grip, mm per second.)
GraspCloserConfig power_grasp(const HandMotorVector& closed_rad);

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
  const GraspCloserConfig& config() const { return config_; }

 private:
  GraspCloserConfig config_;
  HandMotorVector from_{};
  HandMotorVector target_{};
  HandMotorVector contact_rad_{};
  std::array<bool, kHandMotors> contact_{};
  double last_t_s_ = 0.0;
};

}  // namespace teleop::hand
