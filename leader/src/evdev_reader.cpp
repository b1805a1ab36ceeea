#include "evdev_reader.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

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

// "046d:c626": the vendor and product ids; false for anything else
bool parse_usb_id(const std::string& device, unsigned& vendor, unsigned& product) {
  char end = 0;
  return device.size() == 9 && device[4] == ':' &&
         std::sscanf(device.c_str(), "%4x:%4x%c", &vendor, &product, &end) == 2;
}

}  // namespace

bool input_device_matches(const std::string& device, const std::string& path, const libevdev* found) {
  if (is_path(device)) return device == path;
  unsigned vendor = 0;
  unsigned product = 0;
  if (parse_usb_id(device, vendor, product)) {
    return static_cast<unsigned>(libevdev_get_id_vendor(found)) == vendor &&
           static_cast<unsigned>(libevdev_get_id_product(found)) == product;
  }
  const char* name = libevdev_get_name(found);
  return name != nullptr && device == name;
}

EvdevReader::EvdevReader(std::string device, std::string what) : what_(std::move(what)), device_spec_(std::move(device)) {
  if (!open_device()) throw std::runtime_error(what_ + ": no input device " + device_spec_);
}

EvdevReader::~EvdevReader() { close_device(); }

void EvdevReader::start() {
  drain();
  reader_ = std::thread([this] { run(); });
}

void EvdevReader::stop() {
  stop_.store(true);
  if (reader_.joinable()) reader_.join();
  close_device();
}

void EvdevReader::refuse(const std::string& problem) {
  close_device();
  throw std::runtime_error(what_ + ": " + description_ + " " + problem);
}

void EvdevReader::require(unsigned type, unsigned code, const char* kind) {
  if (libevdev_has_event_code(device_, type, code) == 0) {
    refuse(std::string("has no ") + kind + " " + libevdev_event_code_get_name(type, code));
  }
}

bool EvdevReader::open_device() {
  std::vector<std::string> candidates;
  if (is_path(device_spec_)) {
    candidates.push_back(device_spec_);
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
    if (input_device_matches(device_spec_, path, device)) {
      fd_ = fd;
      device_ = device;
      // the first device found names it; one found again after a loss may sit at another node
      if (description_.empty()) description_ = path + " (" + libevdev_get_name(device) + ")";
      connected_.store(true, std::memory_order_release);
      return true;
    }
    libevdev_free(device);
    ::close(fd);
  }
  return false;
}

void EvdevReader::close_device() {
  if (device_ != nullptr) libevdev_free(device_);
  if (fd_ >= 0) ::close(fd_);
  device_ = nullptr;
  fd_ = -1;
}

// every pending event, then the device's state as libevdev keeps it (also across a SYN_DROPPED,
// when it resynchronises from the kernel)
void EvdevReader::drain() {
  input_event ev{};
  int rc = 0;
  do {
    rc = libevdev_next_event(device_, LIBEVDEV_READ_FLAG_NORMAL, &ev);
    if (rc == LIBEVDEV_READ_STATUS_SUCCESS) on_event(ev);
    while (rc == LIBEVDEV_READ_STATUS_SYNC) rc = libevdev_next_event(device_, LIBEVDEV_READ_FLAG_SYNC, &ev);
  } while (rc == LIBEVDEV_READ_STATUS_SUCCESS);
  if (rc != -EAGAIN) {  // -ENODEV: unplugged
    close_device();
    connected_.store(false, std::memory_order_release);
    losses_.fetch_add(1, std::memory_order_relaxed);
    on_lost();
    return;
  }
  on_drained(*device_);
}

void EvdevReader::run() {
  runtime::name_own_thread("input");
  using namespace std::chrono_literals;
  while (!stop_.load()) {
    if (device_ == nullptr) {
      // gone: look for it again twice a second
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
