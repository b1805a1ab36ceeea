#pragma once
// Which robot a node drives is chosen in its configuration (`follower.hardware: mujoco`) from the
// backends its executable registered: the node sees only RobotHardware, so a real arm (a Franka,
// a UR) is added as a backend beside the simulation without touching the node.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/robot/robot_hardware.h"

namespace teleop::robot {

/// A backend's settings, read from the node's section while its configuration is read (before it
/// joins the network); it builds the robot once the node starts.
class HardwareSpec {
 public:
  virtual ~HardwareSpec() = default;
  /// The backend's name, as in the configuration.
  virtual const char* backend() const = 0;
  /// Builds the arm for a control loop of `period_s`. Setup time; throws naming what fails.
  virtual std::unique_ptr<RobotHardware> make(double period_s) const = 0;
};

/// Backends by name. Setup time only.
class HardwareRegistry {
 public:
  /// Reads a backend's own keys of the node's section (throws ConfigError naming the key).
  using Parser = std::function<std::shared_ptr<const HardwareSpec>(const ConfigNode& section)>;

  void add(std::string name, Parser parser);
  /// The backend named by `section.hardware` (default: the first added) with its settings.
  /// Throws ConfigError naming the key and the backends there are.
  std::shared_ptr<const HardwareSpec> parse(const ConfigNode& section) const;

 private:
  std::vector<std::pair<std::string, Parser>> backends_;
};

}  // namespace teleop::robot
