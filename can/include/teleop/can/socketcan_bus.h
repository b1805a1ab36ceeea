#pragma once
// CanBus on a Linux SocketCAN raw socket (PF_CAN / CAN_RAW) bound to one interface (can0,
// vcan0, ...). Classic CAN frames only.
//   - send(): non-blocking write; on ENOBUFS / EAGAIN (the interface's tx queue is full) it
//     retries a bounded number of times with a short pause, counts every retry, and then gives
//     up with kWouldBlock (counted as tx_dropped).
//   - receive(): poll() with the timeout, then recvmsg() with the kernel receive timestamp
//     (SO_TIMESTAMPNS) and the socket's drop counter (SO_RXQ_OVFL -> rx_overruns).
//   - error frames are enabled (CAN_RAW_ERR_FILTER: bus-off, controller problems, restarted)
//     and update state(); they are handed to the caller as frames with CanFrame::kError set.
//   - optional receive filters (CAN_RAW_FILTER): only the listed ids pass.
// send() and receive() may be called from different threads; neither allocates.

#include <atomic>
#include <chrono>
#include <span>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "teleop/can/can_bus.h"

namespace teleop::can {

/// One CAN_RAW_FILTER entry: a frame passes when (frame id & mask) == (id & mask).
struct CanIdFilter {
  uint32_t id = 0;
  uint32_t mask = 0;  // 0: every frame passes
  bool extended = false;
};

struct SocketCanOptions {
  /// Receive filters; empty = receive everything. Error frames pass regardless.
  std::vector<CanIdFilter> filters;
  /// Receive the frames this socket sent itself (CAN_RAW_RECV_OWN_MSGS).
  bool receive_own = false;
  /// send(): retries after ENOBUFS / EAGAIN before giving up, and the pause between them.
  unsigned send_retries = 3;
  std::chrono::microseconds retry_pause{100};
  /// SO_RCVBUF request in bytes (0: the kernel default).
  int receive_buffer_bytes = 0;
};

/// Thrown by SocketCanBus's constructor: what failed, on which interface, and why (strerror).
class SocketCanError : public std::runtime_error {
 public:
  SocketCanError(const std::string& what, int error) : std::runtime_error(what), error_(error) {}
  /// The errno of the failing call.
  int error() const { return error_; }

 private:
  int error_;
};

struct SocketCanStats {
  CanBusStats bus;
  uint64_t send_retries = 0;  // ENOBUFS / EAGAIN retries in send()
  uint64_t bus_off_events = 0;
  uint64_t controller_problems = 0;
  uint64_t restarts = 0;
};

/// Every CANopen frame addressed to `node` or broadcast (NMT, SYNC, SDO request, RPDOs 1-4):
/// the filter set an emulated or real drive needs.
std::vector<CanIdFilter> canopen_node_filters(uint8_t node);
/// Every frame a CANopen master needs from these nodes: EMCY, TPDO1, SDO response, heartbeat.
std::vector<CanIdFilter> canopen_master_filters(std::span<const uint8_t> nodes);

class SocketCanBus final : public CanBus {
 public:
  /// Opens a raw CAN socket on `interface`. Throws SocketCanError naming the interface and the
  /// cause (e.g. "address family not supported" on a kernel without CAN, "no such device").
  explicit SocketCanBus(const std::string& interface, const SocketCanOptions& options = {});
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  CanStatus send(const CanFrame& frame) override;
  CanStatus receive(CanFrame& frame, std::chrono::nanoseconds timeout) override;
  /// Like receive(), also returning the kernel receive timestamp (CLOCK_REALTIME, ns; 0 if the
  /// kernel gave none).
  CanStatus receive(CanFrame& frame, std::chrono::nanoseconds timeout, int64_t& timestamp_ns);
  CanBusState state() const override;
  CanBusStats stats() const override;
  SocketCanStats socket_stats() const;

  /// Replaces the receive filters (empty: everything).
  void set_filters(const std::vector<CanIdFilter>& filters);
  const std::string& interface() const { return interface_; }
  int fd() const { return fd_; }

 private:
  void handle_error_frame(const CanFrame& frame);

  std::string interface_;
  SocketCanOptions options_;
  int fd_ = -1;
  std::atomic<CanBusState> state_{CanBusState::kErrorActive};
  std::atomic<uint64_t> tx_frames_{0}, rx_frames_{0}, tx_dropped_{0}, rx_overruns_{0}, error_frames_{0};
  std::atomic<uint64_t> send_retries_{0}, bus_off_{0}, ctrl_problems_{0}, restarts_{0};
  uint32_t last_drop_count_ = 0;  // SO_RXQ_OVFL is cumulative; touched by the receiver only
};

}  // namespace teleop::can
