#pragma once
// A robot arm as the leader's haptic master on a host without CAN, for the leader's tests:
// `leader.device: robot_arm` on `hardware: canopen_emulated` (test/emulator/emulated_can_arm.h: the
// CANopen master and the emulated drives turning the MuJoCo Panda, in process), Panda-sized
// drives two per bus as the shipped config/nodes/leader_canopen_arm.yaml places them.

#include <string>

#include "emulated_can_arm.h"
#include "teleop/leader/arm_devices.h"
#include "teleop/robot/mujoco_backend.h"

namespace teleop::test {

/// The keys of the `leader:` section that make the master (two-space indented); `extra`: more keys
/// of leader.robot_arm (four-space indented).
inline std::string emulated_master_keys(const std::string& extra = "") {
  std::string drives;
  const char* buses[] = {"can0", "can0", "can1", "can1", "can2", "can2", "can3"};
  for (int k = 0; k < 7; ++k) {
    drives += std::string("      - {bus: ") + buses[k] + ", node: " + std::to_string(k + 1) +
              ", gear_ratio: 100, gear_efficiency: 0.9, encoder_ticks_per_rev: 65536, rated_torque_mnm: " +
              (k < 4 ? "100, max_torque_nm: 87}\n" : "15, max_torque_nm: 12}\n");
  }
  return "  device: robot_arm\n  robot_arm:\n    hardware: canopen_emulated\n    mujoco: {model: " +
         std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml, keyframe: ready}\n    canopen:\n      drives:\n" +
         drives + extra;
}

/// The robots the master may be: the simulation and the emulated CAN arm.
inline robot::HardwareRegistry emulated_robots() {
  robot::HardwareRegistry robots;
  robot::add_mujoco_backend(robots);
  emulator::test::add_emulated_canopen_backend(robots);
  return robots;
}

/// A device registry with robot_arm on those robots.
inline leader::DeviceRegistry emulated_master_devices() {
  leader::DeviceRegistry devices;
  leader::add_robot_arm_device(devices, emulated_robots());
  return devices;
}

}  // namespace teleop::test
