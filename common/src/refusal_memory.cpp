#include "teleop/common/refusal_memory.h"

namespace teleop {

RefusalMemory::Entry* RefusalMemory::find_or_add(const WriterId& writer) {
  for (size_t i = 0; i < used_; ++i) {
    if (entries_[i].writer == writer) return &entries_[i];
  }
  Entry* slot = nullptr;
  if (used_ < kWriters) {
    slot = &entries_[used_++];
  } else {
    slot = &entries_[next_];
    next_ = (next_ + 1) % kWriters;
  }
  *slot = Entry{writer, 0};
  return slot;
}

bool RefusalMemory::rate_allows(int64_t now_mono_ns) {
  if (now_mono_ns - window_start_ns_ >= 1'000'000'000) {
    window_start_ns_ = now_mono_ns;
    reports_in_window_ = 0;
  }
  return reports_in_window_++ < kReportsPerSecond;
}

bool RefusalMemory::first(const WriterId& writer, uint32_t cause, int64_t now_mono_ns) {
  Entry* entry = find_or_add(writer);
  const uint32_t bit = uint32_t{1} << (cause & 31u);
  if ((entry->causes & bit) != 0) return false;
  // a report the rate refuses stays unreported: the writer's next refusal may get through
  if (!rate_allows(now_mono_ns)) return false;
  entry->causes |= bit;
  return true;
}

}  // namespace teleop
