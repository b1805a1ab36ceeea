#pragma once
// The misbehaviour a test or an operator asks of the drive (EmulatedDrive's injection calls and
// object 0x2F00): a silent heartbeat, a jammed motor, PDOs dropped or delayed, SDO refused.
// Raising a fault is the CiA 402 device's (Cia402Device::raise_fault). The delayed TPDOs wait in
// a fixed queue here, so the drive stays allocation-free.

#include <array>
#include <cstddef>
#include <cstdint>

#include "drive_link.h"
#include "teleop/can/can_frame.h"

namespace teleop::drive {

class FaultInjection {
 public:
  static constexpr size_t kDelayQueue = 16;

  explicit FaultInjection(DriveLink& link) : link_(link) {}

  // what is in force
  bool heartbeat_suppressed() const { return heartbeat_suppressed_; }
  bool stalled() const { return stalled_; }
  bool sdo_refused() const { return sdo_refused_; }
  /// PDOs still to drop (EmulatedDrive::kDropForever: until set to 0).
  uint32_t tpdos_to_drop() const { return drop_tpdos_; }
  uint32_t rpdos_to_drop() const { return drop_rpdos_; }

  // the injection calls (EmulatedDrive's and object 0x2F00's)
  void set_heartbeat_suppressed(bool suppressed) { heartbeat_suppressed_ = suppressed; }
  void set_stalled(bool stalled) { stalled_ = stalled; }
  void set_sdo_refused(bool refused) { sdo_refused_ = refused; }
  void drop_tpdos(uint32_t count) { drop_tpdos_ = count; }
  void drop_rpdos(uint32_t count) { drop_rpdos_ = count; }
  void set_tpdo_delay(double seconds);

  /// True when this received RPDO is to be dropped (counted).
  bool drop_rpdo();
  /// A sampled TPDO: dropped, queued for later, or sent now (all counted).
  void emit_tpdo(const can::CanFrame& frame, int64_t now_ns);
  /// Sends the delayed TPDOs whose time has come, oldest first.
  void release_delayed(int64_t now_ns);
  /// Communication reset: the delayed TPDOs are gone.
  void clear_delayed() { delayed_count_ = 0; }

 private:
  struct DelayedFrame {
    can::CanFrame frame;
    int64_t release_ns = 0;
  };

  DriveLink& link_;
  bool heartbeat_suppressed_ = false;
  bool stalled_ = false;
  bool sdo_refused_ = false;
  uint32_t drop_tpdos_ = 0;
  uint32_t drop_rpdos_ = 0;
  int64_t tpdo_delay_ns_ = 0;
  std::array<DelayedFrame, kDelayQueue> delayed_{};
  size_t delayed_count_ = 0;
};

}  // namespace teleop::drive
