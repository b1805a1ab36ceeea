#pragma once
// The pose and velocity of one body of a simulation, as a tracking system beside the real robot
// would measure it. The follower publishes it for its tracked objects (object_pose_feed.h); the
// twin compares its own copy of the object with it (object_correction.h). Real-time safe.

#include <mujoco/mujoco.h>

#include <array>

namespace teleop::sim {

struct BodyState {
  /// The body frame's origin, world frame [m].
  std::array<double, 3> position_m{};
  /// The body frame's orientation in the world, unit quaternion (w, x, y, z).
  std::array<double, 4> orientation_wxyz{1.0, 0.0, 0.0, 0.0};
  /// Velocity of the body frame's origin, world-aligned [m/s].
  std::array<double, 3> linear_mps{};
  /// Angular velocity, world-aligned [rad/s].
  std::array<double, 3> angular_radps{};
};

/// `body`'s state after the last mj_step/mj_forward of `d` (needs d's positions and velocities).
BodyState body_state(const mjModel* m, const mjData* d, int body);

}  // namespace teleop::sim
