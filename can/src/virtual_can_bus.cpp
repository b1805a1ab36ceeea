#include "teleop/can/virtual_can_bus.h"

#include <linux/can/error.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "teleop/can/bus_load.h"

namespace teleop::can {
namespace detail {

// one endpoint's controller: a fixed ring of received frames and its error state
struct VirtualEndpointState {
  explicit VirtualEndpointState(size_t capacity) : ring(capacity) {}

  // all fields are guarded by the bus mutex
  std::vector<CanFrame> ring;
  size_t head = 0;
  size_t count = 0;
  std::condition_variable frame_available;
  CanBusState state = CanBusState::kErrorActive;
  CanBusStats stats;

  void push(const CanFrame& frame) {
    if (count == ring.size()) {
      ++stats.rx_overruns;
      return;
    }
    ring[(head + count) % ring.size()] = frame;
    ++count;
    frame_available.notify_one();
  }
  CanFrame pop() {
    const CanFrame frame = ring[head];
    head = (head + 1) % ring.size();
    --count;
    return frame;
  }
};

struct VirtualBusCore {
  mutable std::mutex mutex;
  std::vector<VirtualEndpointState*> endpoints;
  VirtualBusTraffic traffic;
};

}  // namespace detail

// ---------------------------------------------------------------------------------------------

VirtualCanEndpoint::VirtualCanEndpoint(std::shared_ptr<detail::VirtualBusCore> core, std::string name, size_t capacity)
    : core_(std::move(core)), state_(std::make_unique<detail::VirtualEndpointState>(capacity)), name_(std::move(name)) {
  std::lock_guard lock(core_->mutex);
  core_->endpoints.push_back(state_.get());
}

VirtualCanEndpoint::~VirtualCanEndpoint() {
  std::lock_guard lock(core_->mutex);
  auto& eps = core_->endpoints;
  eps.erase(std::remove(eps.begin(), eps.end(), state_.get()), eps.end());
}

CanStatus VirtualCanEndpoint::send(const CanFrame& frame) {
  std::lock_guard lock(core_->mutex);
  if (state_->state == CanBusState::kBusOff || state_->state == CanBusState::kDown) {
    ++state_->stats.tx_dropped;
    return CanStatus::kBusOff;
  }
  // error frames come from controllers, not from applications
  if (!frame.valid() || frame.error()) {
    ++state_->stats.tx_dropped;
    return CanStatus::kInvalidFrame;
  }
  for (detail::VirtualEndpointState* ep : core_->endpoints) {
    // a controller that is down or bus-off does not take part in the bus
    if (ep != state_.get() && ep->state != CanBusState::kBusOff && ep->state != CanBusState::kDown) ep->push(frame);
  }
  ++state_->stats.tx_frames;
  const CanIdFormat format = frame.extended() ? CanIdFormat::kExtended : CanIdFormat::kStandard;
  const uint32_t bytes = frame.rtr() ? 0 : frame.dlc;  // a remote frame carries no data field
  ++core_->traffic.frames;
  core_->traffic.bits_nominal += frame_bits_nominal(bytes, format);
  core_->traffic.bits_worst_case += frame_bits_worst_case(bytes, format);
  return CanStatus::kOk;
}

CanStatus VirtualCanEndpoint::receive(CanFrame& frame, std::chrono::nanoseconds timeout) {
  std::unique_lock lock(core_->mutex);
  if (state_->count == 0) {
    if (timeout <= std::chrono::nanoseconds::zero()) return CanStatus::kTimeout;
    const bool got = state_->frame_available.wait_for(lock, timeout, [this] { return state_->count > 0; });
    if (!got) return CanStatus::kTimeout;
  }
  frame = state_->pop();
  ++state_->stats.rx_frames;
  if (frame.error()) ++state_->stats.error_frames;
  return CanStatus::kOk;
}

CanBusState VirtualCanEndpoint::state() const {
  std::lock_guard lock(core_->mutex);
  return state_->state;
}

CanBusStats VirtualCanEndpoint::stats() const {
  std::lock_guard lock(core_->mutex);
  return state_->stats;
}

size_t VirtualCanEndpoint::pending() const {
  std::lock_guard lock(core_->mutex);
  return state_->count;
}

void VirtualCanEndpoint::set_state(CanBusState state) {
  std::lock_guard lock(core_->mutex);
  const bool entering_bus_off = state == CanBusState::kBusOff && state_->state != CanBusState::kBusOff;
  state_->state = state;
  if (entering_bus_off) {
    // what SocketCAN reports to a socket with CAN_ERR_BUSOFF in its error mask
    CanFrame error;
    error.id = CAN_ERR_BUSOFF;
    error.dlc = CAN_ERR_DLC;
    error.flags = CanFrame::kError;
    state_->push(error);
  }
}

// ---------------------------------------------------------------------------------------------

VirtualCanBus::VirtualCanBus(size_t queue_capacity)
    : core_(std::make_shared<detail::VirtualBusCore>()), queue_capacity_(queue_capacity) {
  if (queue_capacity == 0) throw std::invalid_argument("VirtualCanBus: queue_capacity must be > 0");
  core_->endpoints.reserve(64);
}

VirtualCanBus::~VirtualCanBus() = default;

std::unique_ptr<VirtualCanEndpoint> VirtualCanBus::open(std::string name) {
  return std::unique_ptr<VirtualCanEndpoint>(new VirtualCanEndpoint(core_, std::move(name), queue_capacity_));
}

size_t VirtualCanBus::endpoints() const {
  std::lock_guard lock(core_->mutex);
  return core_->endpoints.size();
}

VirtualBusTraffic VirtualCanBus::traffic() const {
  std::lock_guard lock(core_->mutex);
  return core_->traffic;
}

}  // namespace teleop::can
