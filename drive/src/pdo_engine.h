#pragma once
// The drive's process data objects (CiA 301): two RPDOs and two TPDOs with their communication
// parameters (0x1400/0x1401, 0x1800/0x1801) and mappings (0x1600/0x1601, 0x1A00/0x1A01).
// RPDOs write their mapped objects on reception or at the next SYNC; TPDOs read theirs at SYNC
// (every n-th, or acyclic on change) or on their event timer. The values go through the object
// dictionary given to each call; what leaves goes through fault injection (drop, delay).

#include <array>
#include <cstddef>
#include <cstdint>

#include "cia402_device.h"
#include "fault_injection.h"
#include "nmt_slave.h"
#include "teleop/can/cia301.h"

namespace teleop::drive {

class ObjectDictionary;

class PdoEngine {
 public:
  static constexpr size_t kChannels = 2;  // RPDO1/2, TPDO1/2

  PdoEngine(DriveLink& link, FaultInjection& faults, NmtSlave& nmt, const Cia402Device& device);

  /// Communication reset: RPDO1 0x200+id [controlword, target] and TPDO1 0x180+id [position,
  /// current, statusword] valid and synchronous; RPDO2 and TPDO2 (mapped [velocity, error code])
  /// prepared but not valid.
  void reset(can::NodeId node);
  /// NMT start: the TPDOs' SYNC counters and event timers begin again.
  void start(int64_t now_ns);
  /// Leaving operational: synchronous RPDOs waiting for a SYNC are forgotten.
  void forget_pending();

  /// True when `frame` is one of this drive's valid RPDOs (operational only): it was consumed.
  bool receive(const can::CanFrame& frame, ObjectDictionary& objects);
  /// A SYNC: waiting RPDOs take effect, then synchronous TPDOs are sampled.
  void sync(ObjectDictionary& objects, int64_t now_ns);
  /// Event-driven TPDOs (transmission type 254/255) whose event timer expired.
  void service_event_timers(const ObjectDictionary& objects, int64_t now_ns);

  // --- the PDO parameter objects: channel n (0 or 1) of the receive or transmit side ---
  uint32_t communication(bool transmit, size_t n, uint8_t subindex) const;
  uint32_t write_communication(bool transmit, size_t n, uint8_t subindex, uint32_t value, int64_t now_ns);
  uint32_t mapping(bool transmit, size_t n, uint8_t subindex) const;
  uint32_t write_mapping(bool transmit, size_t n, uint8_t subindex, uint32_t value);

 private:
  using Values = std::array<uint64_t, can::PdoMapping::kMaxEntries>;
  struct Channel {
    uint32_t cob_id = 0;  // bit 31 set = not valid
    uint8_t transmission_type = 1;
    uint16_t inhibit_100us = 0;
    uint16_t event_timer_ms = 0;
    std::array<uint32_t, can::PdoMapping::kMaxEntries> map_raw{};
    uint8_t map_count = 0;
    can::PdoMapping mapping;
    // runtime
    uint8_t sync_count = 0;
    bool pending = false;  // received synchronous RPDO waiting for the next SYNC
    Values pending_values{};
    int64_t next_event_ns = 0;
    can::CanFrame last_sent;
    bool sent_once = false;
    bool valid() const { return (cob_id & 0x80000000u) == 0; }
  };

  Channel& channel(bool transmit, size_t n) { return transmit ? tpdo_[n] : rpdo_[n]; }
  const Channel& channel(bool transmit, size_t n) const { return transmit ? tpdo_[n] : rpdo_[n]; }
  void handle_rpdo(Channel& pdo, const can::CanFrame& frame, ObjectDictionary& objects);
  static void apply(const Channel& pdo, const Values& values, ObjectDictionary& objects);
  void send_tpdo(Channel& pdo, const ObjectDictionary& objects, int64_t now_ns);

  DriveLink& link_;
  FaultInjection& faults_;
  NmtSlave& nmt_;
  const Cia402Device& device_;
  std::array<Channel, kChannels> rpdo_{};
  std::array<Channel, kChannels> tpdo_{};
};

}  // namespace teleop::drive
