#pragma once
// Buttons of a Linux input device beside the operator's device (docs/stop_chain.md): a USB
// emergency-stop button or a foot pedal (they enumerate as keyboards or joysticks), read through
// libevdev by a thread of its own and merged into the leader's button word, so `leader.buttons`
// maps them like the device's own. A stop input that disappears (unplugged, a cut cable) reads as
// its emergency stop pressed until it is back: for a stop input, silence must stop.

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "evdev_reader.h"
#include "teleop/common/config.h"

namespace teleop::leader {

struct ButtonInputConfig {
  /// A device node (/dev/input/by-id/..., /dev/input/event3), a USB vendor:product id or the
  /// name the device reports ("Pedal Co. USB Foot Switch"), found among /dev/input/event* at
  /// start and after a loss (evdev_reader.h).
  std::string device;
  /// Each evdev key code read, and the leader button it is.
  std::vector<std::pair<unsigned, int>> keys;
};

/// Each key of `keys` ({KEY_PAUSE: 0, BTN_0: 1}: key names as the kernel spells them) and the
/// leader button it is. Throws ConfigError naming an unknown key name or a button out of range.
std::vector<std::pair<unsigned, int>> read_key_buttons(const ConfigNode& keys);

/// Reads `leader.button_input: {device: ..., keys: {KEY_PAUSE: 0, BTN_0: 1}}` (key names as the
/// kernel spells them); nullopt without it. Throws ConfigError naming an unknown key name or a
/// button out of range.
std::optional<ButtonInputConfig> parse_button_input(const ConfigNode& leader_section);

class ButtonInput final : public EvdevReader {
 public:
  /// Opens the device and starts reading it. Throws std::runtime_error naming the device when it
  /// is not there or lacks a key the config names. `lost_word`: what word() reads while the
  /// device is gone. Setup time.
  ButtonInput(ButtonInputConfig config, uint32_t lost_word);
  ~ButtonInput() override { stop(); }

  /// The leader buttons held now. Real-time safe (an atomic load).
  uint32_t word() const { return word_.load(std::memory_order_acquire); }

 private:
  void on_drained(const libevdev& device) override;
  void on_lost() override { word_.store(lost_word_, std::memory_order_release); }

  ButtonInputConfig config_;
  uint32_t lost_word_;
  std::atomic<uint32_t> word_{0};
};

}  // namespace teleop::leader
