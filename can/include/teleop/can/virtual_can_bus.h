#pragma once
// An in-memory CAN bus for tests and the emulator: any number of endpoints share one bus, and
// every frame one endpoint sends is delivered to all the others (not back to the sender, like a
// SocketCAN socket without CAN_RAW_RECV_OWN_MSGS), in one global order: the order of the
// send() calls. Deterministic (no threads inside, no timing in the delivery; only a blocking
// receive() waits on a clock), thread-safe (one mutex per bus), and allocation-free after
// open(): each endpoint's receive queue is a fixed ring; a full queue drops the frame for that
// endpoint and counts an overrun, as a controller's FIFO would.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "teleop/can/can_bus.h"

namespace teleop::can {

namespace detail {
struct VirtualBusCore;
struct VirtualEndpointState;
}  // namespace detail

/// One node on a VirtualCanBus. Owned by its user; may outlive the bus object (the shared
/// core stays alive until the last endpoint is gone).
class VirtualCanEndpoint final : public CanBus {
 public:
  ~VirtualCanEndpoint() override;
  VirtualCanEndpoint(const VirtualCanEndpoint&) = delete;
  VirtualCanEndpoint& operator=(const VirtualCanEndpoint&) = delete;

  /// Delivers the frame to every other endpoint; kBusOff while set_state(kBusOff/kDown),
  /// kInvalidFrame for a frame that is not valid(). Never blocks (on anything but the bus mutex).
  CanStatus send(const CanFrame& frame) override;
  /// Pops the oldest frame; waits up to `timeout` for one (0: poll without waiting).
  CanStatus receive(CanFrame& frame, std::chrono::nanoseconds timeout) override;
  CanBusState state() const override;
  CanBusStats stats() const override;

  const std::string& name() const { return name_; }
  /// Frames waiting in this endpoint's queue.
  size_t pending() const;
  /// Fault injection: puts this endpoint's controller in an error state. Entering kBusOff
  /// queues a SocketCAN-style error frame (id CAN_ERR_BUSOFF, dlc 8) for this endpoint and makes
  /// send() fail until the state is set back to kErrorActive.
  void set_state(CanBusState state);

 private:
  friend class VirtualCanBus;
  VirtualCanEndpoint(std::shared_ptr<detail::VirtualBusCore> core, std::string name, size_t capacity);

  std::shared_ptr<detail::VirtualBusCore> core_;
  std::unique_ptr<detail::VirtualEndpointState> state_;
  std::string name_;
};

/// Totals of everything sent on the bus, with the bit counts of bus_load.h.
struct VirtualBusTraffic {
  uint64_t frames = 0;
  uint64_t bits_nominal = 0;
  uint64_t bits_worst_case = 0;
};

class VirtualCanBus {
 public:
  /// queue_capacity: frames each endpoint can hold before it overruns.
  explicit VirtualCanBus(size_t queue_capacity = 4096);
  ~VirtualCanBus();
  VirtualCanBus(const VirtualCanBus&) = delete;
  VirtualCanBus& operator=(const VirtualCanBus&) = delete;

  /// A new endpoint (allocates its queue; call at setup). The name is for diagnostics.
  std::unique_ptr<VirtualCanEndpoint> open(std::string name = {});
  /// Number of endpoints currently open.
  size_t endpoints() const;
  VirtualBusTraffic traffic() const;

 private:
  std::shared_ptr<detail::VirtualBusCore> core_;
  size_t queue_capacity_;
};

}  // namespace teleop::can
