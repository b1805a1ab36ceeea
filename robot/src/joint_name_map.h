#pragma once
// Which entry of a ROS 2 JointState is which of the follower's joints: ROS 2 matches joints by
// name, never by order (joint_state_broadcaster orders them as the robot's URDF or its hardware
// interfaces happen to list them).

#include <cstddef>
#include <string>
#include <vector>

namespace teleop::robot {

class JointNameMap {
 public:
  /// `joints`: the robot's names in the follower's order; `ignored`: other names a state may carry.
  JointNameMap(std::vector<std::string> joints, std::vector<std::string> ignored);

  /// Maps a state's `names`: true when each joint is there once and every other name is ignored.
  /// No allocation (the DDS thread maps every sample).
  bool map(const std::vector<std::string>& names);
  /// Where joint `i` is in the last state mapped.
  size_t index(size_t i) const { return index_[i]; }
  size_t joints() const { return joints_.size(); }
  /// What is wrong with `names`, naming the joints missing, repeated and unexpected (setup time).
  std::string mismatch(const std::vector<std::string>& names) const;

 private:
  bool ignored(const std::string& name) const;

  std::vector<std::string> joints_;
  std::vector<std::string> ignored_;
  std::vector<size_t> index_;
};

}  // namespace teleop::robot
