#pragma once
// `teleop topic hz`: the rate of a topic over a window of arrivals, the spread of the period, the
// samples' age on arrival and the gaps in each writer's sequence numbers. Pure: the caller gives
// the times.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>

#include "teleop/common/stream_session.h"

namespace teleop::tools {

struct RateStats {
  /// Arrivals in the window and over the whole run.
  uint64_t window = 0;
  uint64_t received = 0;
  /// Sequence numbers skipped within each writer's run (a new writer starts its own count).
  uint64_t lost = 0;
  double rate_hz = 0.0;  ///< (window - 1) / the window's time span
  double period_mean_s = 0.0;
  double period_min_s = 0.0;
  double period_max_s = 0.0;
  double period_std_s = 0.0;
  /// Source stamp to arrival (CLOCK_REALTIME; across hosts as good as their clock sync) [s].
  double age_mean_s = 0.0;
  double age_max_s = 0.0;
  /// The first and last sequence numbers of the newest writer, and the span between its first and
  /// last arrival [s]: received + lost = last - first + 1 for one writer.
  uint64_t first_seq = 0;
  uint64_t last_seq = 0;
  double span_s = 0.0;
};

class RateMeter {
 public:
  explicit RateMeter(size_t window) : capacity_(window < 2 ? 2 : window) {}

  /// One arrival: when (CLOCK_MONOTONIC ns), its age (ns), its writer and sequence number.
  void add(int64_t arrival_ns, int64_t age_ns, const WriterId& writer, uint64_t seq);
  RateStats stats() const;
  /// Arrivals so far (cheap: no statistics computed).
  uint64_t received() const { return received_; }

 private:
  struct Arrival {
    int64_t t_ns;
    int64_t age_ns;
  };
  struct WriterRun {
    uint64_t first_seq = 0;
    uint64_t last_seq = 0;
    int64_t first_ns = 0;
    int64_t last_ns = 0;
  };
  size_t capacity_;
  std::deque<Arrival> arrivals_;
  std::map<std::array<uint8_t, 16>, WriterRun> writers_;
  WriterId newest_writer_;
  uint64_t received_ = 0;
  uint64_t lost_ = 0;
};

}  // namespace teleop::tools
