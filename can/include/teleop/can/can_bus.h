#pragma once
// The edge between the CANopen stack and a CAN controller: send a frame without blocking,
// receive one with a timeout, report the controller's error state. Implementations: the
// in-memory VirtualCanBus endpoint (tests, emulator) and, later, SocketCAN.

#include <chrono>
#include <cstdint>

#include "teleop/can/can_frame.h"

namespace teleop::can {

enum class [[nodiscard]] CanStatus : uint8_t{
    kOk,
    kTimeout,       // receive: no frame within the timeout
    kWouldBlock,    // send: transmit queue full, frame not sent
    kBusOff,        // the controller is bus-off: nothing is sent
    kInvalidFrame,  // send: the frame is not valid() (id range, dlc)
    kClosed,        // the bus or the interface is gone
    kIoError,       // any other failure of the underlying interface
};
const char* to_string(CanStatus status);

/// Error state of the controller (ISO 11898-1 fault confinement, plus "down").
enum class CanBusState : uint8_t { kErrorActive, kErrorWarning, kErrorPassive, kBusOff, kDown };
const char* to_string(CanBusState state);

struct CanBusStats {
  uint64_t tx_frames = 0;     // frames accepted for sending
  uint64_t rx_frames = 0;     // frames handed out by receive()
  uint64_t tx_dropped = 0;    // frames refused by send() (queue full, bus-off, invalid)
  uint64_t rx_overruns = 0;   // frames lost because the receive queue was full
  uint64_t error_frames = 0;  // error frames received
};

/// One node's access to a CAN bus. Thread-safety and real-time behaviour are the
/// implementation's to state; both implementations here allow send() and receive() from
/// different threads and do not allocate after construction.
class CanBus {
 public:
  virtual ~CanBus() = default;

  /// Queues a frame for sending; never blocks.
  virtual CanStatus send(const CanFrame& frame) = 0;
  /// Waits up to `timeout` for a frame (0: poll). kOk fills `frame`.
  virtual CanStatus receive(CanFrame& frame, std::chrono::nanoseconds timeout) = 0;
  /// The controller's current error state.
  [[nodiscard]] virtual CanBusState state() const = 0;
  [[nodiscard]] virtual CanBusStats stats() const = 0;
};

}  // namespace teleop::can
