#pragma once
// Which input device a leader drives is chosen in its configuration (`leader.device: haptic_arm`)
// from the devices its executable registered: the node sees only LeaderDevice, so a real device
// (a haptic arm of a lab's own) is added beside the simulated ones without touching the node.
// The leader's counterpart of the follower's robot::HardwareRegistry.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

/// What the leader knows of the device's place once the node starts: the loop's period and the
/// hand (of a one- or two-handed station) the device is for.
struct DeviceSetup {
  double period_s = 1e-3;
  size_t joints = 7;
  /// The script's home (leader.home_rad): the pose the operator's intent is measured from.
  JointVector home_rad{};
  /// The arm class's model file (leader.arm_model, or the hand's model in leader.arms); "" if none.
  std::string arm_model;
  /// The end-effector site of that model (leader.ee_site).
  std::string ee_site = "ee_site";
};

/// A device's settings, read from the `leader:` section while the configuration is read (before
/// the node joins the network); it builds the device once the node starts.
class DeviceSpec {
 public:
  virtual ~DeviceSpec() = default;
  /// The device's name, as in the configuration.
  virtual const char* device() const = 0;
  /// The device moves a Cartesian pose (DeviceState::position_m, ...), not joints: it can drive
  /// only the architectures that map the device in Cartesian space (pfc, pfc_tdpa).
  virtual bool cartesian() const { return false; }
  /// Builds the device. Setup time; throws naming what fails.
  virtual std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const = 0;
};

/// Devices by name. Setup time only.
class DeviceRegistry {
 public:
  /// Reads a device's own keys of the `leader:` section (by convention its subsection of the
  /// device's name, `leader.haptic_arm`) and throws ConfigError naming the key. It only reads (and
  /// may load the files it names); opening the device is make()'s.
  using Parser = std::function<std::shared_ptr<const DeviceSpec>(const ConfigNode& section)>;

  /// Throws std::logic_error for a name registered twice. The name is also the key of the device's
  /// subsection, so it is none of the leader's own keys (`motion`, `hand`, `arms`, ...).
  void add(std::string name, Parser parser);
  /// The device named by `section.device` (default: the first added) with its settings. Throws
  /// ConfigError naming the key, the devices there are and the nearest to a mistyped name. The
  /// subsection of another registered device is checked by its parser too, so that one file can
  /// carry the settings of several and switch with `--set leader.device=...`.
  std::shared_ptr<const DeviceSpec> parse(const ConfigNode& section) const;
  /// The registered names, in the order added.
  std::vector<std::string> names() const;

 private:
  std::vector<std::pair<std::string, Parser>> devices_;
};

}  // namespace teleop::leader
