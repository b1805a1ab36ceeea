#pragma once
// A group of emulated drives and the plant they turn, stepped together (the hand's nine, an
// arm's joints): each drive on its own CanBus endpoint, turning either its own link
// (EmulatedDrive's default DC-motor link) or one channel of a shared plant such as the MuJoCo
// hand or arm (SharedDrivePlant, drive_plant.h). With a shared plant the drives advance in the
// plant's steps (1 ms for the MuJoCo hand), every drive one step, then the plant one step, so that
// the plant sees all the torques of the same interval; time that does not fill a step waits for
// the next call. Used by the emulators, the tests and the benchmarks.
//
// Construction allocates and throws (std::invalid_argument); step() is real-time safe.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "teleop/can/can_bus.h"
#include "teleop/drive/drive_plant.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

/// One drive of the group: its bus endpoint (not owned), its configuration, and, with a shared
/// plant, the plant channel it turns.
struct DriveGroupNode {
  can::CanBus* bus = nullptr;
  EmulatedDriveConfig config;
  size_t channel = 0;
};

class DriveGroup {
 public:
  /// Drives turning their own links (`plant` null) or the channels of `plant` (which must
  /// outlive this). Throws std::invalid_argument for a null bus, a channel the plant does not
  /// have or one turned by two drives, a plant step that is not positive, and whatever
  /// EmulatedDrive throws for its configuration.
  explicit DriveGroup(const std::vector<DriveGroupNode>& nodes, SharedDrivePlant* plant = nullptr);

  /// Advances every drive (and the shared plant) by dt_s of simulated time; with a shared
  /// plant, in whole plant steps (a remainder carries over to the next call).
  void step(double dt_s);

  size_t drives() const { return drives_.size(); }
  EmulatedDrive& drive(size_t i) { return *drives_[i]; }
  const EmulatedDrive& drive(size_t i) const { return *drives_[i]; }
  /// The shared plant, or null when every drive turns its own link.
  SharedDrivePlant* plant() const { return plant_; }
  /// Simulated time advanced so far (the plant's, in whole steps, with a shared plant) [s].
  double time_s() const { return static_cast<double>(time_ns_) * 1e-9; }
  /// Plant steps taken (0 without a shared plant).
  uint64_t plant_steps() const { return plant_steps_; }

 private:
  std::vector<std::unique_ptr<EmulatedDrive>> drives_;
  SharedDrivePlant* plant_ = nullptr;
  int64_t plant_step_ns_ = 0;
  double plant_step_s_ = 0.0;
  int64_t pending_ns_ = 0;
  int64_t time_ns_ = 0;
  uint64_t plant_steps_ = 0;
};

}  // namespace teleop::drive
