#pragma once
// A Linux input device (/dev/input/event*) read through libevdev by a thread of its own, found by
// its node, its vendor:product id or the name it reports, and found again after it went away
// (unplugged, a cut cable): what the leader's input devices share (button_input.h,
// input_device.h). A subclass sees each event as it comes, the device's state once the pending
// events are drained, and the loss; it publishes what it makes of them to the control loop
// through atomics of its own, so the loop never waits on the device.

#include <linux/input.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

struct libevdev;

namespace teleop::leader {

/// How `device` names an input device: a path has a '/', "046d:c626" is a USB vendor:product
/// (hexadecimal), anything else is the name the device reports.
bool input_device_matches(const std::string& device, const std::string& path, const libevdev* found);

class EvdevReader {
 public:
  /// A subclass has stopped the thread (stop()) by now; this closes the device.
  virtual ~EvdevReader();
  EvdevReader(const EvdevReader&) = delete;
  EvdevReader& operator=(const EvdevReader&) = delete;

  bool connected() const { return connected_.load(std::memory_order_acquire); }
  /// Times the device went away since start.
  uint64_t losses() const { return losses_.load(std::memory_order_relaxed); }
  /// The device it reads: its node and the name it reports.
  const std::string& description() const { return description_; }

 protected:
  /// `what`: the configuration key, for errors ("leader.button_input"). Opens the device; throws
  /// std::runtime_error naming it when there is none. Setup time.
  EvdevReader(std::string device, std::string what);
  /// Stops the thread: a subclass calls it first in its destructor, before its members go.
  void stop();
  /// Starts the thread: a subclass calls it last in its constructor, after its checks.
  void start();
  /// Throws std::runtime_error naming the device and `problem`, and closes it. Setup time.
  [[noreturn]] void refuse(const std::string& problem);
  /// Refuses the device unless it reports `code` of `type` ("has no key BTN_5"; `kind`: "key",
  /// "axis"). Setup time.
  void require(unsigned type, unsigned code, const char* kind);

  /// Each event read, in order (not those of a resynchronisation). On the reader's thread.
  virtual void on_event(const input_event& event) { (void)event; }
  /// The pending events were read: libevdev's state (keys, absolute axes) is the device's now.
  virtual void on_drained(const libevdev& device) = 0;
  /// The device went away; it is looked for again twice a second.
  virtual void on_lost() = 0;

 private:
  bool open_device();
  void close_device();
  void run();
  void drain();

  std::string what_;
  std::string device_spec_;
  int fd_ = -1;
  libevdev* device_ = nullptr;
  std::string description_;
  std::atomic<bool> connected_{false};
  std::atomic<uint64_t> losses_{0};
  std::atomic<bool> stop_{false};
  std::thread reader_;
};

}  // namespace teleop::leader
