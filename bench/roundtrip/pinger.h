#pragma once
// The pinger's variants: each starts its own echo, paces its sends through run_paced and
// returns what it measured.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "echo_process.h"
#include "roundtrip.h"
#include "rtt_recorder.h"
#include "teleop/common/histogram.h"

namespace teleop::bench {

struct VariantResult {
  Variant variant{};
  uint64_t window_begin = 0;  // first measured sequence number
  uint64_t sent = 0;          // samples sent in the measured window
  uint64_t send_failed = 0;
  RttRecorder::Snapshot rtt;
  uint64_t overruns = 0;  // pacer, measured window only
  uint64_t skipped = 0;
  DurationHistogram lateness;  // release time - deadline, measured window only
  int64_t cpu_ping_ns = 0;     // CPU time of the pinger in the measured window
  int64_t cpu_echo_ns = -1;    // and of the echo (-1: unreadable)
};

/// Sends sample `seq` (1, 2, ...); false if it was refused.
using SendFn = std::function<bool(uint64_t seq)>;

/// Paced sending: warm-up (at least opt.warmup samples and until a first reply came back), then
/// opt.samples measured samples, then a grace period for the last replies.
void run_paced(const Options& opt, RttRecorder& rec, EchoProcess& echo, const SendFn& send, VariantResult& result);

/// dds-udp, dds-shm or dds-sec: the teleop transport, leader/joint_state out, follower/joint_state back.
VariantResult run_dds_variant(Variant v, const Options& opt);

/// raw-udp: datagrams of `payload_size` bytes, filled from `fill` (the serialized sample).
VariantResult run_raw_udp_variant(const Options& opt, size_t payload_size, const std::vector<unsigned char>& fill);

/// Seconds as a short human string ("10", "0.5").
std::string seconds_text(double s);

}  // namespace teleop::bench
