#include "input_device.h"

#include <libevdev/libevdev.h>

#include <array>
#include <atomic>
#include <stdexcept>

#include "teleop/common/clock.h"

namespace teleop::leader {

// The reader's side: each axis's deflection and, for a relative one, when it last came; the
// keys' word. Written by the reader thread, read by the control loop, each value on its own.
class AxisInput final : public EvdevReader {
 public:
  static constexpr size_t kMaxAxes = 16;

  explicit AxisInput(const InputDeviceConfig& config) : EvdevReader(config.device, "leader." + config.kind), config_(config) {
    for (const InputAxis& a : config_.axes) require(a.type, a.code, "axis");
    for (const auto& [code, button] : config_.keys) require(EV_KEY, code, "key");
    start();
  }
  ~AxisInput() override { stop(); }

  /// Axis k's deflection now, in [-1, 1] before the dead band. Real-time safe.
  double deflection(size_t k, int64_t now_ns) const {
    const double value = values_[k].load(std::memory_order_acquire);
    if (config_.axes[k].type != EV_REL) return value;
    const auto silent_ns = static_cast<double>(now_ns - reported_ns_[k].load(std::memory_order_acquire));
    return silent_ns > config_.release_s * 1e9 ? 0.0 : value;
  }
  uint32_t word() const { return word_.load(std::memory_order_acquire); }

 private:
  void on_event(const input_event& event) override {
    if (event.type != EV_REL) return;
    for (size_t k = 0; k < config_.axes.size(); ++k) {
      if (config_.axes[k].type != EV_REL || config_.axes[k].code != event.code) continue;
      values_[k].store(static_cast<double>(event.value) / config_.relative_full_scale, std::memory_order_release);
      reported_ns_[k].store(monotonic_now_ns(), std::memory_order_release);
    }
  }
  // absolute axes and keys as libevdev keeps them: an axis about the middle of its range
  void on_drained(const libevdev& device) override {
    for (size_t k = 0; k < config_.axes.size(); ++k) {
      const InputAxis& a = config_.axes[k];
      if (a.type != EV_ABS) continue;
      const input_absinfo* range = libevdev_get_abs_info(&device, a.code);
      const double half = 0.5 * (range->maximum - range->minimum);
      const double middle = 0.5 * (range->maximum + range->minimum);
      const double value = half > 0.0 ? (libevdev_get_event_value(&device, EV_ABS, a.code) - middle) / half : 0.0;
      values_[k].store(value, std::memory_order_release);
    }
    uint32_t word = 0;
    for (const auto& [code, button] : config_.keys) {
      if (libevdev_get_event_value(&device, EV_KEY, code) != 0) word |= 1u << button;
    }
    word_.store(word, std::memory_order_release);
  }
  void on_lost() override {
    for (auto& v : values_) v.store(0.0, std::memory_order_release);
    word_.store(0, std::memory_order_release);
  }

  const InputDeviceConfig& config_;
  std::array<std::atomic<double>, kMaxAxes> values_{};
  std::array<std::atomic<int64_t>, kMaxAxes> reported_ns_{};
  std::atomic<uint32_t> word_{0};
};

InputDevice::InputDevice(const InputDeviceConfig& config, double period_s)
    : config_(config), pose_(config.motion, period_s) {
  if (config_.axes.size() > AxisInput::kMaxAxes) throw std::invalid_argument("leader." + config_.kind + ": too many axes");
  input_ = std::make_unique<AxisInput>(config_);
}

InputDevice::~InputDevice() = default;

const std::string& InputDevice::description() const { return input_->description(); }
uint64_t InputDevice::losses() const { return input_->losses(); }

bool InputDevice::read(DeviceState& state) {
  const bool connected = input_->connected();
  std::array<double, 6> deflection{};
  if (connected) {
    const int64_t now_ns = monotonic_now_ns();
    for (size_t k = 0; k < config_.axes.size(); ++k) {
      const InputAxis& a = config_.axes[k];
      deflection[static_cast<size_t>(a.component)] += a.sign * input_->deflection(k, now_ns);
    }
  }
  pose_.step(deflection);
  const Eigen::Quaterniond& q = pose_.orientation();
  for (int i = 0; i < 3; ++i) state.position_m[static_cast<size_t>(i)] = pose_.position()[i];
  state.orientation_wxyz = {q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 6; ++i) state.twist[static_cast<size_t>(i)] = pose_.twist()[i];
  state.buttons |= input_->word();
  return connected;
}

}  // namespace teleop::leader
