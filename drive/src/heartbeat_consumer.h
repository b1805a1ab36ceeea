#pragma once
// The drive's heartbeat consumer (CiA 301, object 0x1016): it watches the heartbeats of up to
// kEntries nodes, its master's above all. An entry's watch starts with the first heartbeat heard
// from its node after the entry is written (CiA 301); a silence longer than the entry's time is
// one timeout, reported once, and the watch starts again when the node is heard again.
// Plain arithmetic, real-time safe.

#include <array>
#include <cstdint>

#include "teleop/can/cia301.h"

namespace teleop::drive {

class HeartbeatConsumer {
 public:
  static constexpr uint8_t kEntries = 2;  // 0x1016 sub 1..2

  /// Sub 1..kEntries: (node << 16) | ms.
  uint32_t entry(uint8_t subindex) const { return entries_[subindex - 1].raw; }
  /// 0, or the SDO abort code: a second active entry for a node already watched (0x06040043).
  uint32_t set_entry(uint8_t subindex, uint32_t value);
  /// Communication reset: every entry off.
  void reset() { entries_ = {}; }

  /// A heartbeat (or boot-up) from `node` now.
  void heard(can::NodeId node, int64_t now_ns);
  /// True once for each watched node that has been silent longer than its time.
  bool timed_out(int64_t now_ns);

 private:
  struct Entry {
    uint32_t raw = 0;
    bool watching = false;  // heard since the entry was written, and not timed out since
    int64_t last_ns = 0;
    can::NodeId node() const { return static_cast<can::NodeId>(raw >> 16); }
    int64_t time_ns() const { return int64_t{static_cast<uint16_t>(raw)} * 1'000'000; }
    bool active() const { return node() != 0 && time_ns() > 0; }
  };
  std::array<Entry, kEntries> entries_{};
};

}  // namespace teleop::drive
