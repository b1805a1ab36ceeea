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
#include <thread>
#include <utility>
#include <vector>

#include "teleop/common/config.h"

struct libevdev;

namespace teleop::leader {

struct ButtonInputConfig {
  /// A device node (/dev/input/by-id/..., /dev/input/event3) or the name the device reports
  /// ("Pedal Co. USB Foot Switch"), found among /dev/input/event* at start and after a loss.
  std::string device;
  /// Each evdev key code read, and the leader button it is.
  std::vector<std::pair<unsigned, int>> keys;
};

/// Reads `leader.button_input: {device: ..., keys: {KEY_PAUSE: 0, BTN_0: 1}}` (key names as the
/// kernel spells them); nullopt without it. Throws ConfigError naming an unknown key name or a
/// button out of range.
std::optional<ButtonInputConfig> parse_button_input(const ConfigNode& leader_section);

class ButtonInput {
 public:
  /// Opens the device and starts reading it. Throws std::runtime_error naming the device when it
  /// is not there or lacks a key the config names. `lost_word`: what word() reads while the
  /// device is gone. Setup time.
  ButtonInput(ButtonInputConfig config, uint32_t lost_word);
  ~ButtonInput();
  ButtonInput(const ButtonInput&) = delete;
  ButtonInput& operator=(const ButtonInput&) = delete;

  /// The leader buttons held now. Real-time safe (an atomic load).
  uint32_t word() const { return word_.load(std::memory_order_acquire); }
  bool connected() const { return connected_.load(std::memory_order_acquire); }
  /// Times the device went away since start.
  uint64_t losses() const { return losses_.load(std::memory_order_relaxed); }
  /// The device it reads (its node and the name it reports).
  const std::string& description() const { return description_; }

 private:
  bool open_device();
  void close_device();
  void run();
  void drain();

  ButtonInputConfig config_;
  uint32_t lost_word_;
  int fd_ = -1;
  libevdev* device_ = nullptr;
  std::string description_;
  std::atomic<uint32_t> word_{0};
  std::atomic<bool> connected_{false};
  std::atomic<uint64_t> losses_{0};
  std::atomic<bool> stop_{false};
  std::thread reader_;
};

}  // namespace teleop::leader
