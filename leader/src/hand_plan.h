#pragma once
// What the simulated operator's hand does: a HandCommand plan for the teleop_hand node, as the
// arm's OperatorMotion is for the arm. Keyframes of the 9 motor targets (SVH channel order, motor
// angles [rad]) and current limits [A] at times since the start; between two keyframes the
// targets move along a smoothstep (rest at both ends), the current limits switch at the later
// keyframe; after the last one it holds. The leader publishes a sample every cycle on
// teleop/hand/command (`leader.hand.plan`, config/nodes/leader_hand.yaml); a data glove would
// take this class's place (docs/hand.md, "The hand reaches the operator"). Real-time safe.

#include <array>
#include <cstddef>
#include <vector>

#include "teleop/common/config.h"

namespace teleop::leader {

constexpr size_t kHandMotors = 9;  // msg::HAND_MOTORS
using HandMotors = std::array<double, kHandMotors>;

struct HandKeyframe {
  double t_s = 0.0;
  HandMotors position_rad{};
  /// 0: the node's default current limit.
  HandMotors current_limit_a{};
};

class HandPlan {
 public:
  /// Throws std::invalid_argument for no keyframe, times that do not increase or start below 0,
  /// or a non-finite value.
  explicit HandPlan(std::vector<HandKeyframe> keyframes);

  /// The targets and current limits at `t_s` after the start.
  void sample(double t_s, HandMotors& position_rad, HandMotors& current_limit_a) const;
  const std::vector<HandKeyframe>& keyframes() const { return keyframes_; }

 private:
  std::vector<HandKeyframe> keyframes_;
};

/// Reads `section.plan`: a list of {t_s, position_rad: [9], current_limit_a: [9] (optional)}.
/// Throws ConfigError naming the file, the key and the problem.
HandPlan parse_hand_plan(const ConfigNode& section);

}  // namespace teleop::leader
