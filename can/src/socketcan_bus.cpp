#include "teleop/can/socketcan_bus.h"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>

#include "teleop/can/cia301.h"

namespace teleop::can {
namespace {

std::string describe(const std::string& interface, const char* what, int error) {
  return "SocketCAN " + interface + ": " + what + ": " + std::strerror(error);
}

// SO_RXQ_OVFL may be missing from very old headers
#ifndef SO_RXQ_OVFL
#define SO_RXQ_OVFL 40
#endif

std::vector<can_filter> to_kernel(const std::vector<CanIdFilter>& filters) {
  std::vector<can_filter> out;
  out.reserve(filters.size());
  for (const auto& f : filters) {
    can_filter k{};
    k.can_id = f.extended ? ((f.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (f.id & CAN_SFF_MASK);
    // match the frame format too, and never pass RTR frames of data filters
    k.can_mask = (f.extended ? (f.mask & CAN_EFF_MASK) : (f.mask & CAN_SFF_MASK)) | CAN_EFF_FLAG | CAN_RTR_FLAG;
    out.push_back(k);
  }
  return out;
}

int64_t to_ns(std::chrono::nanoseconds d) { return d.count(); }

}  // namespace

std::vector<CanIdFilter> canopen_node_filters(uint8_t node) {
  std::vector<CanIdFilter> f;
  f.push_back({cob::kNmt, 0x7FF, false});
  f.push_back({cob::kSync, 0x7FF, false});
  f.push_back({static_cast<uint32_t>(cob::kSdoRx + node), 0x7FF, false});
  for (uint32_t base : {0x200u, 0x300u, 0x400u, 0x500u}) f.push_back({base + node, 0x7FF, false});
  return f;
}

std::vector<CanIdFilter> canopen_master_filters(std::span<const uint8_t> nodes) {
  std::vector<CanIdFilter> f;
  for (const uint8_t node : nodes) {
    for (uint32_t base : {uint32_t{cob::kEmcy}, uint32_t{cob::kTpdo1}, uint32_t{cob::kSdoTx}, uint32_t{cob::kHeartbeat}}) {
      f.push_back({base + node, 0x7FF, false});
    }
  }
  return f;
}

SocketCanBus::SocketCanBus(const std::string& interface, const SocketCanOptions& options)
    : interface_(interface), options_(options) {
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    throw SocketCanError("SocketCAN: invalid interface name '" + interface + "'", EINVAL);
  }
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) {
    const int e = errno;
    throw SocketCanError(describe(interface, "cannot open a raw CAN socket (does the kernel have CAN?)", e), e);
  }
  auto fail = [&](const char* what) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    throw SocketCanError(describe(interface, what, e), e);
  };
  const unsigned index = ::if_nametoindex(interface.c_str());
  if (index == 0) fail("no such interface");

  const can_err_mask_t err_mask = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED | CAN_ERR_TX_TIMEOUT;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) != 0) fail("CAN_RAW_ERR_FILTER");
  const int own = options.receive_own ? 1 : 0;
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own)) != 0) fail("CAN_RAW_RECV_OWN_MSGS");
  const int one = 1;
  if (::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof(one)) != 0) fail("SO_TIMESTAMPNS");
  if (::setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof(one)) != 0) fail("SO_RXQ_OVFL");
  if (options.receive_buffer_bytes > 0 &&
      ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &options.receive_buffer_bytes, sizeof(int)) != 0) {
    fail("SO_RCVBUF");
  }
  if (!options.filters.empty()) {
    const auto k = to_kernel(options.filters);
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, k.data(), static_cast<socklen_t>(k.size() * sizeof(can_filter))) != 0) {
      fail("CAN_RAW_FILTER");
    }
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(index);
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) fail("bind");
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCanBus::set_filters(const std::vector<CanIdFilter>& filters) {
  const auto k = to_kernel(filters);
  const int rc = filters.empty()
                     ? ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, nullptr, 0)
                     : ::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, k.data(),
                                    static_cast<socklen_t>(k.size() * sizeof(can_filter)));
  if (rc != 0) {
    const int e = errno;
    throw SocketCanError(describe(interface_, "CAN_RAW_FILTER", e), e);
  }
  if (filters.empty()) {
    // a zero-length filter list receives nothing: restore the default "everything" filter
    can_filter all{0, 0};
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, &all, sizeof(all)) != 0) {
      const int e = errno;
      throw SocketCanError(describe(interface_, "CAN_RAW_FILTER", e), e);
    }
  }
}

CanStatus SocketCanBus::send(const CanFrame& frame) {
  if (state_.load() == CanBusState::kBusOff) {
    tx_dropped_.fetch_add(1);
    return CanStatus::kBusOff;
  }
  const auto k = to_linux(frame);
  if (!k.ok() || frame.error()) {
    tx_dropped_.fetch_add(1);
    return CanStatus::kInvalidFrame;
  }
  for (unsigned attempt = 0;; ++attempt) {
    const ssize_t n = ::send(fd_, &k.value(), sizeof(can_frame), MSG_DONTWAIT);
    if (n == static_cast<ssize_t>(sizeof(can_frame))) {
      tx_frames_.fetch_add(1);
      return CanStatus::kOk;
    }
    const int e = n < 0 ? errno : EIO;
    if ((e == ENOBUFS || e == EAGAIN) && attempt < options_.send_retries) {
      send_retries_.fetch_add(1);
      // wait for queue space, at most the retry pause (ENOBUFS does not wake poll: a sleep then)
      pollfd p{fd_, POLLOUT, 0};
      const int ms = static_cast<int>(std::max<int64_t>(1, options_.retry_pause.count() / 1000));
      if (e == EAGAIN) {
        (void)::poll(&p, 1, ms);
      } else {
        timespec ts{0, static_cast<long>(options_.retry_pause.count()) * 1000L};
        ::nanosleep(&ts, nullptr);
      }
      continue;
    }
    if (e == EINTR) continue;
    tx_dropped_.fetch_add(1);
    if (e == ENOBUFS || e == EAGAIN) return CanStatus::kWouldBlock;
    if (e == ENETDOWN || e == ENXIO || e == ENODEV) {
      state_.store(CanBusState::kDown);
      return CanStatus::kClosed;
    }
    return CanStatus::kIoError;
  }
}

CanStatus SocketCanBus::receive(CanFrame& frame, std::chrono::nanoseconds timeout) {
  int64_t ts = 0;
  return receive(frame, timeout, ts);
}

CanStatus SocketCanBus::receive(CanFrame& frame, std::chrono::nanoseconds timeout, int64_t& timestamp_ns) {
  timestamp_ns = 0;
  timespec deadline{};
  ::clock_gettime(CLOCK_MONOTONIC, &deadline);
  const int64_t deadline_ns = deadline.tv_sec * 1000000000LL + deadline.tv_nsec + to_ns(timeout);
  for (;;) {
    can_frame k{};
    iovec iov{&k, sizeof(k)};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(uint32_t))];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof(control);
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      const int e = errno;
      if (e == EINTR) continue;
      if (e != EAGAIN && e != EWOULDBLOCK) {
        if (e == ENETDOWN || e == ENODEV) {
          state_.store(CanBusState::kDown);
          return CanStatus::kClosed;
        }
        return CanStatus::kIoError;
      }
      timespec now{};
      ::clock_gettime(CLOCK_MONOTONIC, &now);
      const int64_t left = deadline_ns - (now.tv_sec * 1000000000LL + now.tv_nsec);
      if (left <= 0) return CanStatus::kTimeout;
      pollfd p{fd_, POLLIN, 0};
      const timespec wait{static_cast<time_t>(left / 1000000000LL), static_cast<long>(left % 1000000000LL)};
      const int rc = ::ppoll(&p, 1, &wait, nullptr);
      if (rc < 0 && errno != EINTR) return CanStatus::kIoError;
      continue;
    }
    if (n != static_cast<ssize_t>(sizeof(can_frame))) continue;  // not a classic frame: skip
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof(ts));
        timestamp_ns = ts.tv_sec * 1000000000LL + ts.tv_nsec;
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        uint32_t drops = 0;
        std::memcpy(&drops, CMSG_DATA(c), sizeof(drops));
        if (drops != last_drop_count_) {
          rx_overruns_.fetch_add(static_cast<uint32_t>(drops - last_drop_count_));
          last_drop_count_ = drops;
        }
      }
    }
    const auto f = from_linux(k);
    if (!f.ok()) continue;  // malformed: drop
    frame = f.value();
    if (frame.error()) handle_error_frame(frame);
    rx_frames_.fetch_add(1);
    return CanStatus::kOk;
  }
}

void SocketCanBus::handle_error_frame(const CanFrame& frame) {
  error_frames_.fetch_add(1);
  if ((frame.id & CAN_ERR_RESTARTED) != 0) {
    restarts_.fetch_add(1);
    state_.store(CanBusState::kErrorActive);
  }
  if ((frame.id & CAN_ERR_CRTL) != 0) {
    ctrl_problems_.fetch_add(1);
    const uint8_t ctrl = frame.dlc > 1 ? frame.data[1] : 0;
    if ((ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      state_.store(CanBusState::kErrorPassive);
    } else if ((ctrl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) {
      state_.store(CanBusState::kErrorWarning);
    } else if ((ctrl & CAN_ERR_CRTL_ACTIVE) != 0) {
      state_.store(CanBusState::kErrorActive);
    }
  }
  if ((frame.id & CAN_ERR_BUSOFF) != 0) {
    bus_off_.fetch_add(1);
    state_.store(CanBusState::kBusOff);
  }
}

CanBusState SocketCanBus::state() const { return state_.load(); }

CanBusStats SocketCanBus::stats() const {
  CanBusStats s;
  s.tx_frames = tx_frames_.load();
  s.rx_frames = rx_frames_.load();
  s.tx_dropped = tx_dropped_.load();
  s.rx_overruns = rx_overruns_.load();
  s.error_frames = error_frames_.load();
  return s;
}

SocketCanStats SocketCanBus::socket_stats() const {
  SocketCanStats s;
  s.bus = stats();
  s.send_retries = send_retries_.load();
  s.bus_off_events = bus_off_.load();
  s.controller_problems = ctrl_problems_.load();
  s.restarts = restarts_.load();
  return s;
}

}  // namespace teleop::can
