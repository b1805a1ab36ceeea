#pragma once
// position_position and mmt at the follower, and a follower without a teleoperation section: it
// tracks the joint impedance commands it receives (from the leader, or from the twin) as they are.

#include "follower_architecture.h"

namespace teleop::follower {

class JointCommandFollower final : public FollowerArchitecture {
 public:
  bool cartesian() const override { return false; }
  const ValidCommand* correct(const ValidCommand& /*active*/, bool /*running*/,
                              const control::Vector6& /*wrench*/) override {
    return nullptr;
  }
};

}  // namespace teleop::follower
