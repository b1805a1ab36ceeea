#include "nmt_slave.h"

namespace teleop::drive {

using can::NmtState;

NmtSlave::NmtSlave(can::NodeId node, uint16_t default_heartbeat_ms, DriveLink& link)
    : node_(node), default_heartbeat_ms_(default_heartbeat_ms), link_(link) {}

void NmtSlave::restart() {
  initialising_ = true;
  state_ = NmtState::kBootUp;
}

void NmtSlave::boot(int64_t now_ns) {
  initialising_ = false;
  state_ = NmtState::kPreOperational;
  if (const auto boot = can::encode_heartbeat(node_, NmtState::kBootUp); boot.ok()) link_.send(*boot);
  next_heartbeat_ns_ = now_ns + int64_t{heartbeat_ms_} * 1'000'000;
}

void NmtSlave::set_heartbeat_ms(uint16_t ms, int64_t now_ns) {
  heartbeat_ms_ = ms;
  next_heartbeat_ns_ = now_ns + int64_t{heartbeat_ms_} * 1'000'000;
}

void NmtSlave::produce_heartbeat(int64_t now_ns, bool suppressed) {
  const bool producing = !initialising_ && heartbeat_ms_ > 0;
  if (!producing || now_ns < next_heartbeat_ns_) return;
  if (!suppressed) {
    if (const auto hb = can::encode_heartbeat(node_, state_); hb.ok()) {
      link_.send(*hb);
      ++link_.stats().heartbeats_sent;
    }
  }
  const int64_t period_ns = int64_t{heartbeat_ms_} * 1'000'000;
  next_heartbeat_ns_ += period_ns;
  if (next_heartbeat_ns_ <= now_ns) next_heartbeat_ns_ = now_ns + period_ns;  // after a long step
}

void NmtSlave::send_emcy(uint16_t error_code, uint8_t error_register, const std::array<uint8_t, 5>& vendor) {
  if (initialising_ || state_ == NmtState::kStopped) return;
  can::EmcyMessage message;
  message.node = node_;
  message.error_code = error_code;
  message.error_register = error_register;
  message.vendor = vendor;
  if (const auto frame = can::encode_emcy(message); frame.ok()) {
    link_.send(*frame);
    ++link_.stats().emcys_sent;
  }
}

}  // namespace teleop::drive
