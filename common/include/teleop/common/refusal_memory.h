#pragma once
// Which writers were already reported for which kind of refused sample: the first refused sample
// of each kind per writer is logged, the rest only counted. Bounded in writers remembered (the
// oldest is forgotten, and reported again should it come back) and in reports per second (a
// storm of forged writers cannot flood the log). Real-time safe: no allocation.

#include <array>
#include <cstddef>
#include <cstdint>

#include "teleop/common/stream_session.h"

namespace teleop {

class RefusalMemory {
 public:
  static constexpr size_t kWriters = 8;
  static constexpr int kReportsPerSecond = 10;

  /// True when this is the first refusal of `cause` (0..31) for `writer` and the rate allows a report.
  bool first(const WriterId& writer, uint32_t cause, int64_t now_mono_ns);

 private:
  struct Entry {
    WriterId writer{};
    uint32_t causes = 0;
  };
  Entry* find_or_add(const WriterId& writer);
  bool rate_allows(int64_t now_mono_ns);

  std::array<Entry, kWriters> entries_{};
  size_t used_ = 0;
  size_t next_ = 0;  // the slot a new writer replaces once all are used
  int64_t window_start_ns_ = 0;
  int reports_in_window_ = 0;
};

}  // namespace teleop
