#include "fault_injection.h"

#include <cmath>

namespace teleop::drive {

void FaultInjection::set_tpdo_delay(double seconds) {
  tpdo_delay_ns_ = std::isfinite(seconds) && seconds > 0 ? std::llround(seconds * 1e9) : 0;
}

bool FaultInjection::drop_rpdo() {
  if (drop_rpdos_ == 0) return false;
  if (drop_rpdos_ != EmulatedDrive::kDropForever) --drop_rpdos_;
  ++link_.stats().rpdos_dropped;
  return true;
}

void FaultInjection::emit_tpdo(const can::CanFrame& frame, int64_t now_ns) {
  if (drop_tpdos_ > 0) {
    if (drop_tpdos_ != EmulatedDrive::kDropForever) --drop_tpdos_;
    ++link_.stats().tpdos_dropped;
    return;
  }
  if (tpdo_delay_ns_ > 0) {
    if (delayed_count_ == kDelayQueue) {
      ++link_.stats().tpdos_dropped;
      return;
    }
    delayed_[delayed_count_++] = {frame, now_ns + tpdo_delay_ns_};
    return;
  }
  link_.send(frame);
  ++link_.stats().tpdos_sent;
}

void FaultInjection::release_delayed(int64_t now_ns) {
  size_t kept = 0;
  for (size_t i = 0; i < delayed_count_; ++i) {
    if (delayed_[i].release_ns <= now_ns) {
      link_.send(delayed_[i].frame);
      ++link_.stats().tpdos_sent;
    } else {
      delayed_[kept++] = delayed_[i];
    }
  }
  delayed_count_ = kept;
}

}  // namespace teleop::drive
