#pragma once
// The drive's object dictionary: ONE table (object_dictionary.cpp) of every object the drive
// has, each with its size, access, PDO mappability and how it is read and written on the part
// of the drive that owns it. The SDO server and the PDO engine reach the objects only here.

#include <cstdint>

#include "cia402_device.h"
#include "fault_injection.h"
#include "heartbeat_consumer.h"
#include "motor_model.h"
#include "nmt_slave.h"
#include "pdo_engine.h"
#include "servo_controller.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

struct ObjectInfo {
  uint8_t bits = 0;
  bool writable = false;
  bool rx_mappable = false;
  bool tx_mappable = false;
};

/// The parts of one drive that its objects live in.
struct ObjectOwners {
  EmulatedDriveConfig& config;  // identity, rated current; 0x2000 writes the gains
  NmtSlave& nmt;
  PdoEngine& pdos;
  Cia402Device& device;
  const ServoController& servo;
  const MotorModel& motor;
  FaultInjection& faults;
  HeartbeatConsumer& heartbeats;
  const int64_t& now_ns;  // the drive's clock (timers restart on some writes)
};

class ObjectDictionary {
 public:
  explicit ObjectDictionary(const ObjectOwners& owners) : owners_(owners) {}

  /// 0 and the object's description, or the SDO abort code (no such object or subindex).
  static uint32_t find(uint16_t index, uint8_t subindex, ObjectInfo& info);
  /// 0 and the value, or the SDO abort code.
  uint32_t read(uint16_t index, uint8_t subindex, uint32_t& value) const;
  /// 0, or the SDO abort code (read-only, or a value the object refuses).
  uint32_t write(uint16_t index, uint8_t subindex, uint32_t value);

 private:
  ObjectOwners owners_;
};

}  // namespace teleop::drive
