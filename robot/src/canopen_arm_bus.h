#pragma once
// The CANopen side of an arm of CiA 402 torque drives on one CAN bus: the start-up that configures
// every drive by SDO (its PDOs, cyclic synchronous torque, heartbeats both ways, its reaction to a
// lost master), and the cycle: the drives' feedback in, each joint's command and the SYNC out,
// the master's heartbeat, and the supervision of the drives (EMCY, heartbeats, reboots, bus-off).
// The joints' units and the walk to operation enabled are the axes' (cia402_axis.h).
//
// Per drive (node id n), mapped at start-up (docs/robots.md, docs/can_bus_budget.md):
//   RPDO1 0x200 + n, synchronous: controlword 0x6040, target torque 0x6071 (4 bytes)
//   TPDO1 0x180 + n, every SYNC: position 0x6064, torque actual 0x6077, statusword 0x6041 (8 bytes)
// The joint rate is differentiated from the positions (the bus has no room for 0x606C at 1 kHz).
// receive() and send() are real-time safe: no allocation, no waiting.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "canopen_sdo_client.h"
#include "teleop/can/bus_load.h"
#include "teleop/can/can_bus.h"
#include "teleop/can/cia301.h"
#include "teleop/robot/cia402_axis.h"

namespace teleop::robot {

struct CanopenDriveConfig {
  can::NodeId node = 0;
  Cia402AxisConfig axis;
};

struct CanopenBusConfig {
  std::vector<CanopenDriveConfig> drives;  // in the arm's joint order
  can::NodeId master_node = 127;           // the master's heartbeat goes out as 0x700 + this
  uint16_t master_heartbeat_ms = 10;
  uint16_t drive_heartbeat_ms = 10;        // 0x1017 of every drive
  uint16_t master_lost_after_ms = 50;      // the drives' 0x1016 entry for the master's heartbeat
  uint16_t drive_lost_after_ms = 50;       // the master's watch of every drive's heartbeat
  int16_t abort_connection_option = can::cia402::abort_connection::kQuickStop;  // 0x6007
  double sync_period_s = 1e-3;             // 0x1006; the SYNC the master sends
  double bitrate_bps = 1e6;
};

/// Why the bus can no longer drive the arm (the first one seen; it stays until a new start).
enum class BusFault : uint8_t { kNone, kEmcy, kHeartbeatLost, kDriveRebooted, kBusOff, kSendRefused };
const char* to_string(BusFault fault);
struct BusFaultInfo {
  BusFault fault = BusFault::kNone;
  can::NodeId node = 0;       // the drive it concerns (0: the bus itself)
  uint16_t emcy_code = 0;     // for kEmcy
};

struct CanopenBusStats {
  uint64_t syncs = 0;
  uint64_t tpdos = 0;
  uint64_t incomplete_cycles = 0;  // a cycle sent while some drive's feedback had not arrived
  uint64_t emcys = 0;
  uint64_t sends_refused = 0;
};

/// The cyclic traffic of a configuration (SYNC, one RPDO and one TPDO per drive per SYNC, the
/// heartbeats), for the load check at start-up and docs/can_bus_budget.md.
can::BusLoad canopen_bus_load(const CanopenBusConfig& config);

class CanopenArmBus {
 public:
  /// Throws std::invalid_argument for a configuration that cannot run: no drive, node ids
  /// outside 1..127 or twice, the master's id among the drives', timeouts not above the
  /// heartbeat periods, or a worst-case bus load above 70 % (the message gives the load).
  CanopenArmBus(can::CanBus& bus, CanopenBusConfig config);

  /// Start-up: every node pre-operational, each drive checked (a CiA 402 device, its rated torque
  /// as configured) and configured by SDO, then started (NMT) with torque 0; the watch of the
  /// drives' heartbeats starts with the next receive(). Throws std::runtime_error naming the
  /// drive, the object and its answer.
  void configure(const SdoWait& wait, int64_t now_ns);

  /// Takes every frame waiting on the bus into the axes and the supervision. Real-time safe.
  void receive(int64_t now_ns);
  /// Sends each axis's command (set by command()), then the SYNC that applies them, and the
  /// master's heartbeat when it is due, unless `heartbeat` is false: during the start-up walk, so
  /// that the drives (whose watch starts with the first heartbeat) watch their master only once
  /// its cycle runs; the time between the walk and the first cycle (the node's network start-up,
  /// hundreds of milliseconds) would count as a lost master. Real-time safe.
  void send(int64_t now_ns, bool heartbeat = true);

  size_t size() const { return axes_.size(); }
  Cia402Axis& axis(size_t k) { return axes_[k]; }
  const Cia402Axis& axis(size_t k) const { return axes_[k]; }
  /// What send() sends to drive k next.
  void command(size_t k, const AxisCommand& command) { commands_[k] = command; }
  /// Every drive's feedback of the last SYNC has arrived.
  bool feedback_complete() const;
  /// When the SYNC was sent that the oldest of the drives' newest feedback answers (the time the
  /// arm's state was sampled, on the clock send() was given); 0 before any or when it is older
  /// than the last 16 SYNCs.
  int64_t feedback_sampled_ns() const;
  const BusFaultInfo& fault() const { return fault_; }
  const CanopenBusStats& stats() const { return stats_; }
  const CanopenBusConfig& config() const { return config_; }

 private:
  void configure_drive(SdoClient& sdo, const CanopenDriveConfig& drive);
  void take(const can::CanFrame& frame, int64_t now_ns);
  void latch(BusFault fault, can::NodeId node, uint16_t emcy_code = 0);
  int index_of(can::NodeId node) const;
  /// Seconds between the SYNC of `previous_sync` and the last one sent (0: no previous sample).
  double sampling_interval_s(uint64_t previous_sync) const;

  can::CanBus& bus_;
  CanopenBusConfig config_;
  can::PdoMapping rpdo_;
  can::PdoMapping tpdo_;
  std::vector<Cia402Axis> axes_;
  std::vector<AxisCommand> commands_;
  std::vector<int64_t> last_heartbeat_ns_;  // per drive; 0 = none yet
  std::vector<uint64_t> feedback_seen_;     // per drive: the SYNC count its TPDO last answered
  std::array<int64_t, 16> sync_ns_{};       // when SYNC n went out, at n % 16
  BusFaultInfo fault_;
  CanopenBusStats stats_;
  int64_t next_heartbeat_ns_ = 0;
  bool started_ = false;
  bool watching_ = false;  // the drives' heartbeats are watched (from the first receive() on)
};

}  // namespace teleop::robot
