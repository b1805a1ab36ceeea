#include "heartbeat_consumer.h"

namespace teleop::drive {

uint32_t HeartbeatConsumer::set_entry(uint8_t subindex, uint32_t value) {
  const Entry written{value};
  if (written.active()) {
    for (uint8_t s = 1; s <= kEntries; ++s) {
      if (s != subindex && entries_[s - 1].active() && entries_[s - 1].node() == written.node()) {
        return can::sdo_abort::kParameterIncompatible;
      }
    }
  }
  entries_[subindex - 1] = written;  // the watch waits for the node's next heartbeat
  return 0;
}

void HeartbeatConsumer::heard(can::NodeId node, int64_t now_ns) {
  for (Entry& e : entries_) {
    if (e.active() && e.node() == node) {
      e.watching = true;
      e.last_ns = now_ns;
    }
  }
}

bool HeartbeatConsumer::timed_out(int64_t now_ns) {
  bool any = false;
  for (Entry& e : entries_) {
    if (e.active() && e.watching && now_ns - e.last_ns > e.time_ns()) {
      e.watching = false;
      any = true;
    }
  }
  return any;
}

}  // namespace teleop::drive
