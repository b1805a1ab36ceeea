#pragma once
// The drive's CiA 301 network management as a slave: initialising -> boot-up message ->
// pre-operational, the NMT state the master commands, the heartbeat producer (0x1017), and the
// EMCY producer, which CiA 301 allows in pre-operational and operational only.

#include <array>
#include <cstdint>

#include "drive_link.h"
#include "teleop/can/cia301.h"

namespace teleop::drive {

class NmtSlave {
 public:
  NmtSlave(can::NodeId node, uint16_t default_heartbeat_ms, DriveLink& link);

  can::NmtState state() const { return state_; }
  bool initialising() const { return initialising_; }
  bool operational() const { return state_ == can::NmtState::kOperational; }
  void set_state(can::NmtState state) { state_ = state; }
  /// After a reset: initialising again until the next boot().
  void restart();
  /// Ends initialisation: the boot-up message, pre-operational, the heartbeat timer starts.
  void boot(int64_t now_ns);

  /// 0x1017 [ms]; a write restarts the heartbeat timer.
  uint16_t heartbeat_ms() const { return heartbeat_ms_; }
  void set_heartbeat_ms(uint16_t ms, int64_t now_ns);
  /// Communication reset: the heartbeat time from the configuration.
  void reset_communication() { heartbeat_ms_ = default_heartbeat_ms_; }
  /// Sends the heartbeat when due (a suppressed one is skipped, its period kept).
  void produce_heartbeat(int64_t now_ns, bool suppressed);

  /// An emergency message, unless initialising or stopped.
  void send_emcy(uint16_t error_code, uint8_t error_register, const std::array<uint8_t, 5>& vendor);

 private:
  can::NodeId node_;
  uint16_t default_heartbeat_ms_;
  DriveLink& link_;
  bool initialising_ = true;
  can::NmtState state_ = can::NmtState::kBootUp;
  uint16_t heartbeat_ms_ = 0;
  int64_t next_heartbeat_ns_ = 0;
};

}  // namespace teleop::drive
