#pragma once
// The drive's side of the bus: every frame the drive sends goes through here, counted in the
// drive's statistics, which every part of the drive adds to.

#include "teleop/can/can_bus.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

class DriveLink {
 public:
  explicit DriveLink(can::CanBus& bus) : bus_(bus) {}

  /// Sends one frame; a refused send is counted, never retried (a real controller drops it too).
  void send(const can::CanFrame& frame) {
    if (bus_.send(frame) == can::CanStatus::kOk) {
      ++stats_.frames_sent;
    } else {
      ++stats_.send_failures;
    }
  }
  /// The next frame waiting on the bus now (false: none).
  bool receive(can::CanFrame& frame) {
    return bus_.receive(frame, std::chrono::nanoseconds::zero()) == can::CanStatus::kOk;
  }

  EmulatedDriveStats& stats() { return stats_; }
  const EmulatedDriveStats& stats() const { return stats_; }

 private:
  can::CanBus& bus_;
  EmulatedDriveStats stats_;
};

}  // namespace teleop::drive
