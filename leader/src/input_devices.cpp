#include "teleop/leader/input_devices.h"

#include <libevdev/libevdev.h>

#include <array>
#include <string>
#include <utility>

#include "button_input.h"
#include "input_device.h"

namespace teleop::leader {
namespace {

class InputSpec final : public DeviceSpec {
 public:
  explicit InputSpec(InputDeviceConfig config) : config_(std::move(config)) {}
  const char* device() const override { return config_.kind.c_str(); }
  bool cartesian() const override { return true; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    return std::make_unique<InputDevice>(config_, setup.period_s);
  }

 private:
  InputDeviceConfig config_;
};

constexpr std::array<const char*, 6> kComponents{"x", "y", "z", "rx", "ry", "rz"};

// "REL_X: -y": the axis (its type from its prefix) and the component it drives, negated by a '-'
InputAxis read_axis(const ConfigNode& axes, const std::string& name) {
  InputAxis a;
  a.type = name.rfind("REL_", 0) == 0 ? EV_REL : EV_ABS;
  const int code = libevdev_event_code_from_name(static_cast<unsigned>(a.type), name.c_str());
  if (code < 0) throw axes.error(name, "is not an axis the kernel knows (REL_X ... REL_RZ, ABS_X ... ABS_RZ, ABS_HAT0X, ...)");
  a.code = static_cast<unsigned>(code);
  std::string target = axes.get_string(name);
  if (!target.empty() && target.front() == '-') {
    a.sign = -1.0;
    target.erase(0, 1);
  }
  for (size_t i = 0; i < kComponents.size(); ++i) {
    if (target == kComponents[i]) {
      a.component = static_cast<int>(i);
      return a;
    }
  }
  throw axes.error(name, "drives '" + target + "': give one of x y z rx ry rz, negated with a leading -");
}

// the kind's keys over its defaults (the device's own frame, its usual buttons)
std::shared_ptr<const DeviceSpec> parse_input_device(const ConfigNode& leader_section, InputDeviceConfig c) {
  const ConfigNode s = leader_section.child(c.kind);
  c.device = s.get_string("device");
  if (const auto axes = s.optional_child("axes")) {
    c.axes.clear();
    for (const std::string& name : axes->keys()) c.axes.push_back(read_axis(*axes, name));
    if (c.axes.empty()) throw s.error("axes", "names no axis");
  }
  if (const auto keys = s.optional_child("keys")) c.keys = read_key_buttons(*keys);
  c.relative_full_scale = s.get_double("full_scale", Range{1, 1e6}, c.relative_full_scale);
  c.release_s = s.get_double("release_ms", Range{1, 10'000}, c.release_s * 1e3) * 1e-3;
  c.motion.dead_band = s.get_double("dead_band", Range{0, 0.9}, c.motion.dead_band);
  c.motion.linear_speed_mps = s.get_double("linear_speed_mps", Range{0, 2}, c.motion.linear_speed_mps);
  c.motion.angular_speed_radps = s.get_double("angular_speed_radps", Range{0, 6}, c.motion.angular_speed_radps);
  return std::make_shared<InputSpec>(std::move(c));
}

InputAxis axis(unsigned type, unsigned code, int component, double sign = 1.0) { return {type, code, component, sign}; }

// a SpaceNavigator's cap as the kernel reports it, one to one (docs: turn and flip to the desk)
InputDeviceConfig spacemouse_defaults() {
  InputDeviceConfig c;
  c.kind = "spacemouse";
  c.axes = {axis(EV_REL, REL_X, 0), axis(EV_REL, REL_Y, 1), axis(EV_REL, REL_Z, 2),
            axis(EV_REL, REL_RX, 3), axis(EV_REL, REL_RY, 4), axis(EV_REL, REL_RZ, 5)};
  c.keys = {{BTN_0, 0}, {BTN_1, 1}};
  return c;
}

// the left stick moves in the plane (up: forward, +x; right: -y), the right stick up and down
// (up: +z; the kernel's stick y grows downwards) and turns about z
InputDeviceConfig gamepad_defaults() {
  InputDeviceConfig c;
  c.kind = "gamepad";
  c.axes = {axis(EV_ABS, ABS_Y, 0, -1.0), axis(EV_ABS, ABS_X, 1, -1.0), axis(EV_ABS, ABS_RY, 2, -1.0),
            axis(EV_ABS, ABS_RX, 5, -1.0)};
  c.keys = {{BTN_TR, 0}, {BTN_TL, 1}};
  return c;
}

}  // namespace

void add_input_devices(DeviceRegistry& registry) {
  registry.add("spacemouse", [](const ConfigNode& s) { return parse_input_device(s, spacemouse_defaults()); });
  registry.add("gamepad", [](const ConfigNode& s) { return parse_input_device(s, gamepad_defaults()); });
}

}  // namespace teleop::leader
