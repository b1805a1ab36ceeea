#pragma once
// The pinger's variants: each starts its own echo, paces its sends through run_paced and
// returns what it measured.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "echo_process.h"
#include "roundtrip.h"
#include "rtt_recorder.h"
#include "teleop/common/histogram.h"

namespace teleop::bench {

/// A variant's round trips in figures [ns]; -1 = not known.
struct RttFigures {
  uint64_t received = 0;
  int64_t p50_ns = -1;
  int64_t p90_ns = -1;
  int64_t p99_ns = -1;
  int64_t p999_ns = -1;
  int64_t max_ns = -1;
  int64_t min_ns = -1;
};

struct VariantResult {
  Variant variant{};
  int topics = 1;             // samples per cycle
  uint64_t window_begin = 0;  // first measured sequence number
  uint64_t sent = 0;          // cycles sent in the measured window (topics samples each)
  uint64_t send_failed = 0;
  RttRecorder::Snapshot rtt;
  uint64_t overruns = 0;  // pacer, measured window only
  uint64_t skipped = 0;
  DurationHistogram lateness;  // release time - deadline, measured window only
  int64_t cpu_ping_ns = 0;     // CPU time of the pinger in the measured window
  int64_t cpu_echo_ns = -1;    // and of the echo (-1: unreadable)
  /// An outside tool's own figures (ddsperf), in place of `rtt`; losses are then unknown.
  std::optional<RttFigures> external;
  double load_average = -1;  // 1-minute load average when the variant ended
};

/// The figures of a result: from its histogram, or the outside tool's.
RttFigures figures_of(const VariantResult& r);

/// The 1-minute load average (/proc/loadavg); -1 when unreadable.
double load_average_1min();

/// Sends sample `seq` (1, 2, ...); false if it was refused.
using SendFn = std::function<bool(uint64_t seq)>;

/// Paced sending: warm-up (at least opt.warmup samples and until a first reply came back), then
/// opt.samples measured samples, then a grace period for the last replies.
void run_paced(const Options& opt, RttRecorder& rec, EchoProcess& echo, const SendFn& send, VariantResult& result);

/// dds-udp, dds-imp, dds-shm or dds-sec: the teleop transport, leader/joint_state out,
/// follower/joint_state back.
VariantResult run_dds_variant(Variant v, const Options& opt);

/// fastdds: bare Fast DDS (bare_dds.h) on the same topics.
VariantResult run_bare_dds_variant(const Options& opt);

/// ddsperf: Cyclone's ddsperf ping (at opt.rate_hz, `payload_size` bytes) and pong, best effort;
/// its own statistics (it reports half the round trip: doubled here), CPU from /proc.
VariantResult run_ddsperf_variant(const Options& opt, size_t payload_size);

/// raw-udp: datagrams of `payload_size` bytes, filled from `fill` (the serialized sample).
VariantResult run_raw_udp_variant(const Options& opt, size_t payload_size, const std::vector<unsigned char>& fill);

/// Seconds as a short human string ("10", "0.5").
std::string seconds_text(double s);

}  // namespace teleop::bench
