#include "button_input.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "leader_config.h"
#include "teleop/runtime/realtime.h"

namespace teleop::leader {
namespace {

// a device node, opened for reading without blocking; null (and fd -1) when it is not one
libevdev* open_node(const std::string& path, int& fd) {
  fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return nullptr;
  libevdev* device = nullptr;
  if (libevdev_new_from_fd(fd, &device) != 0) {
    ::close(fd);
    fd = -1;
    return nullptr;
  }
  return device;
}

bool is_path(const std::string& device) { return device.find('/') != std::string::npos; }

}  // namespace

std::optional<ButtonInputConfig> parse_button_input(const ConfigNode& leader_section) {
  const auto section = leader_section.optional_child("button_input");
  if (!section) return std::nullopt;
  ButtonInputConfig c;
  c.device = section->get_string("device");
  const ConfigNode keys = section->child("keys");
  for (const std::string& name : keys.keys()) {
    const int code = libevdev_event_code_from_name(EV_KEY, name.c_str());
    if (code < 0) throw keys.error(name, "is not a key the kernel knows (KEY_PAUSE, BTN_0, ... as in linux/input-event-codes.h)");
    c.keys.emplace_back(static_cast<unsigned>(code), static_cast<int>(keys.get_int(name, Range{0, kMaxButton})));
  }
  if (c.keys.empty()) throw section->error("keys", "names no key");
  return c;
}

ButtonInput::ButtonInput(ButtonInputConfig config, uint32_t lost_word) : config_(std::move(config)), lost_word_(lost_word) {
  if (!open_device()) throw std::runtime_error("leader.button_input: no input device " + config_.device);
  for (const auto& [code, button] : config_.keys) {
    if (libevdev_has_event_code(device_, EV_KEY, code) == 0) {
      const std::string name = libevdev_event_code_get_name(EV_KEY, code);
      close_device();
      throw std::runtime_error("leader.button_input: " + description_ + " has no key " + name);
    }
  }
  drain();
  reader_ = std::thread([this] { run(); });
}

ButtonInput::~ButtonInput() {
  stop_.store(true);
  if (reader_.joinable()) reader_.join();
  close_device();
}

bool ButtonInput::open_device() {
  std::vector<std::string> candidates;
  if (is_path(config_.device)) {
    candidates.push_back(config_.device);
  } else {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/dev/input", ec)) {
      if (e.path().filename().string().rfind("event", 0) == 0) candidates.push_back(e.path().string());
    }
  }
  for (const std::string& path : candidates) {
    int fd = -1;
    libevdev* device = open_node(path, fd);
    if (device == nullptr) continue;
    if (is_path(config_.device) || config_.device == libevdev_get_name(device)) {
      fd_ = fd;
      device_ = device;
      description_ = path + " (" + libevdev_get_name(device) + ")";
      connected_.store(true, std::memory_order_release);
      return true;
    }
    libevdev_free(device);
    ::close(fd);
  }
  return false;
}

void ButtonInput::close_device() {
  if (device_ != nullptr) libevdev_free(device_);
  if (fd_ >= 0) ::close(fd_);
  device_ = nullptr;
  fd_ = -1;
}

// every pending event, then the word from the keys' state as libevdev keeps it (also across a
// SYNC_DROPPED, when it resynchronises from the kernel)
void ButtonInput::drain() {
  input_event ev{};
  int rc = 0;
  do {
    rc = libevdev_next_event(device_, LIBEVDEV_READ_FLAG_NORMAL, &ev);
    while (rc == LIBEVDEV_READ_STATUS_SYNC) rc = libevdev_next_event(device_, LIBEVDEV_READ_FLAG_SYNC, &ev);
  } while (rc == LIBEVDEV_READ_STATUS_SUCCESS);
  if (rc != -EAGAIN) {  // -ENODEV: unplugged
    close_device();
    connected_.store(false, std::memory_order_release);
    losses_.fetch_add(1, std::memory_order_relaxed);
    word_.store(lost_word_, std::memory_order_release);
    return;
  }
  uint32_t word = 0;
  for (const auto& [code, button] : config_.keys) {
    if (libevdev_get_event_value(device_, EV_KEY, code) != 0) word |= 1u << button;
  }
  word_.store(word, std::memory_order_release);
}

void ButtonInput::run() {
  runtime::name_own_thread("buttons");
  using namespace std::chrono_literals;
  while (!stop_.load()) {
    if (device_ == nullptr) {
      // gone: look for it again twice a second; the stop stays pressed meanwhile
      if (!open_device()) {
        std::this_thread::sleep_for(500ms);
        continue;
      }
    }
    pollfd readable{fd_, POLLIN, 0};
    if (::poll(&readable, 1, 100) < 0 && errno != EINTR) continue;
    drain();
  }
}

}  // namespace teleop::leader
