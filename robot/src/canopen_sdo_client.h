#pragma once
// The master's SDO client for start-up (configuration before the control loop runs): expedited
// reads and writes, one at a time, each waiting for its answer for at most a timeout. Not for the
// control path: it waits. A refused or unanswered access throws, naming the node, the object and
// what the drive said, so a lab sees which drive refused what.

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "teleop/can/can_bus.h"
#include "teleop/can/cia301.h"

namespace teleop::robot {

/// How the client waits for an answer: it polls the bus every `poll`, at most `timeout` in all;
/// `pump`, if set, runs before each poll (a test steps its emulated drives there; on a real bus
/// the poll's own wait is the time passing).
struct SdoWait {
  std::chrono::nanoseconds poll = std::chrono::milliseconds(1);
  std::chrono::nanoseconds timeout = std::chrono::milliseconds(200);
  std::function<void()> pump;
};

class SdoClient {
 public:
  SdoClient(can::CanBus& bus, SdoWait wait) : bus_(bus), wait_(std::move(wait)) {}

  /// Writes `size` bytes (1..4). Throws std::runtime_error on an abort or no answer.
  void write(can::NodeId node, uint16_t index, uint8_t subindex, uint32_t value, uint8_t size);
  /// Reads an object. Throws std::runtime_error on an abort or no answer.
  uint32_t read(can::NodeId node, uint16_t index, uint8_t subindex);

  /// Frames that arrived while waiting and were not the answer (boot-ups, EMCY, heartbeats):
  /// handed to this, if set, so the caller's supervision misses none.
  std::function<void(const can::CanFrame&)> other_frames;

 private:
  can::SdoMessage transfer(const can::Result<can::CanFrame>& request, can::NodeId node, uint16_t index,
                           uint8_t subindex);

  can::CanBus& bus_;
  SdoWait wait_;
};

/// "node 3, 0x6060:00" for messages.
std::string object_name(can::NodeId node, uint16_t index, uint8_t subindex);

}  // namespace teleop::robot
