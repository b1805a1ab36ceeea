#pragma once
// What an EmulatedDrive is made of: one object per responsibility, built once, in dependency
// order, each given references to the parts it works with.

#include <memory>

#include "cia402_device.h"
#include "drive_link.h"
#include "fault_injection.h"
#include "heartbeat_consumer.h"
#include "link_plant.h"
#include "motor_model.h"
#include "nmt_slave.h"
#include "object_dictionary.h"
#include "pdo_engine.h"
#include "sdo_server.h"
#include "servo_controller.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

struct EmulatedDrive::Parts {
  /// `config` and `now_ns` are the drive's own: the parts read them (and SDO writes the gains).
  /// `plant`: what the motor turns; null: the drive's own link (LinkPlant).
  Parts(can::CanBus& bus, EmulatedDriveConfig& config, const int64_t& now_ns, DrivePlant* plant)
      : own_plant(plant == nullptr ? std::make_unique<LinkPlant>(config.motor, config.initial_position_rad)
                                   : nullptr),
        link(bus),
        motor(config.motor, plant == nullptr ? *own_plant : *plant, config.control.substep_s),
        servo(config.control, config.motor.supply_v, motor.measured_rad()),
        nmt(config.node_id, config.heartbeat_ms, link),
        device(config, servo, motor, nmt),
        faults(link),
        pdos(link, faults, nmt, device),
        objects({config, nmt, pdos, device, servo, motor, faults, heartbeats, now_ns}),
        sdo(config.node_id, link, nmt, faults) {}

  std::unique_ptr<LinkPlant> own_plant;  // null when the plant is someone else's
  DriveLink link;
  MotorModel motor;
  ServoController servo;
  NmtSlave nmt;
  Cia402Device device;
  FaultInjection faults;
  HeartbeatConsumer heartbeats;
  PdoEngine pdos;
  ObjectDictionary objects;
  SdoServer sdo;
};

}  // namespace teleop::drive
