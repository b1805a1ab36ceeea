#include "button_input.h"

#include <libevdev/libevdev.h>

#include <string>

#include "leader_config.h"

namespace teleop::leader {

std::vector<std::pair<unsigned, int>> read_key_buttons(const ConfigNode& keys) {
  std::vector<std::pair<unsigned, int>> read;
  for (const std::string& name : keys.keys()) {
    const int code = libevdev_event_code_from_name(EV_KEY, name.c_str());
    if (code < 0) throw keys.error(name, "is not a key the kernel knows (KEY_PAUSE, BTN_0, ... as in linux/input-event-codes.h)");
    read.emplace_back(static_cast<unsigned>(code), static_cast<int>(keys.get_int(name, Range{0, kMaxButton})));
  }
  return read;
}

std::optional<ButtonInputConfig> parse_button_input(const ConfigNode& leader_section) {
  const auto section = leader_section.optional_child("button_input");
  if (!section) return std::nullopt;
  ButtonInputConfig c;
  c.device = section->get_string("device");
  c.keys = read_key_buttons(section->child("keys"));
  if (c.keys.empty()) throw section->error("keys", "names no key");
  return c;
}

ButtonInput::ButtonInput(ButtonInputConfig config, uint32_t lost_word)
    : EvdevReader(config.device, "leader.button_input"), config_(std::move(config)), lost_word_(lost_word) {
  for (const auto& [code, button] : config_.keys) require(EV_KEY, code, "key");
  start();
}

// the word from the keys' state as libevdev keeps it
void ButtonInput::on_drained(const libevdev& device) {
  uint32_t word = 0;
  for (const auto& [code, button] : config_.keys) {
    if (libevdev_get_event_value(&device, EV_KEY, code) != 0) word |= 1u << button;
  }
  word_.store(word, std::memory_order_release);
}

}  // namespace teleop::leader
