#pragma once
// teleop_roundtrip_bench: leader -> follower -> leader round-trip latency of a msg::JointState
// (7 joints unless --joints says otherwise) at a fixed rate, layer by layer in one run: a raw UDP
// ping-pong on 127.0.0.1 of a payload of the sample's serialized size, bare Fast DDS (a minimal
// participant, writer and reader with default best-effort QoS, no teleop code), the teleop
// transport with the stream preset over UDP, the same with the impairment layer in place but
// transparent, the same over shared memory, and Cyclone's ddsperf ping/pong as an outside
// reference when it is installed. The ratios ours / bare Fast DDS and ours / raw UDP say what
// each layer costs.
//
// The pinger (this process) paces its sends on absolute deadlines (RatePacer + MonotonicClock)
// and stamps each sample with CLOCK_MONOTONIC; the echo side is a separate process (this
// executable re-executed with --role echo, one fresh process per variant) that sends every sample
// straight back unchanged. The RTT is taken on arrival, in the pinger's receive thread (the
// Fast DDS listener thread, or a thread blocked in recv() for raw UDP), not at the loop's next
// cycle: it measures the transport, not the loop phase.
//
// With --pki DIR (made by scripts/make_pki.sh --bench-identity) a third teleop variant runs the
// UDP path with DDS Security on (PKI-DH, access control, AES-GCM-GMAC as the governance says),
// and the report adds the CPU time both processes spent per round trip and the ratios
// security on / off of the same run.
//
// This header holds what both sides share: the options, the variants, the sample, the stop flag
// and the CPU accounting; the roles' entry points are run_pinger (pinger.cpp) and run_echo
// (echo.cpp).

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <teleop/msg/arm.h>

#include "teleop/transport/participant_config.h"

namespace teleop::bench {

struct Options {
  // public
  uint64_t samples = 5000;
  double rate_hz = 1000.0;
  int domain = 77;
  /// Comma-separated variant names (see name_of), or "all".
  std::string variants = "all";
  /// Joints per sample (each of the four sequences).
  size_t joints = 7;
  /// Topics the pinger publishes each cycle (each echoed on its own reply topic).
  int topics = 1;
  std::string pki;
  uint64_t warmup = 200;
  std::string csv;
  std::string summary_csv;
  double timeout_s = 10.0;
  // internal: the echo process
  std::string role = "ping";
  std::string variant;
  int ready_fd = -1;
  double max_seconds = 0.0;
};

/// The pinger's side: runs every variant the options ask for, prints the report (and the CSV).
int run_pinger(const Options& opt);
/// The echo's side (`--role echo`): sends every sample of one variant straight back.
int run_echo(const Options& opt);

// ---------------------------------------------------------------------------------------------
// stop: SIGINT/SIGTERM only set a flag that every loop polls (stop_signal.cpp)

void install_signal_handlers();
bool stop_requested();

/// A stop signal arrived: unwind (which stops the echo) and exit 130.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

/// Throws Interrupted once a stop signal has arrived.
void throw_if_stopped();

// ---------------------------------------------------------------------------------------------
// variants (variant.cpp)

/// In the order a run measures them: the reference first, then layer by layer.
enum class Variant { kRawUdp, kBareDds, kDdsUdp, kDdsImpaired, kDdsShm, kDdsSecure, kDdsPerf };

const char* name_of(Variant v);
std::optional<Variant> parse_variant(const std::string& name);

/// The variants `opt.variants` names ("all": every one that can run here; dds-sec needs --pki,
/// ddsperf its executable). Throws std::invalid_argument naming an unknown variant.
std::vector<Variant> selected_variants(const Options& opt);

/// True for the variants through teleop::transport.
bool is_teleop(Variant v);

/// Whether Cyclone's ddsperf (Debian: cyclonedds-tools) is on PATH.
bool ddsperf_available();

/// The topics of a run: the pinger writes `ping[i]`, the echo answers on `pong[i]`. Topic 0 is
/// the real leader/follower state pair (the secure variant's permissions name it).
struct TopicNames {
  std::vector<std::string> ping;
  std::vector<std::string> pong;
};
TopicNames topic_names(int topics);

/// The participant of one side of a DDS variant; `identity` names the secure variant's
/// certificate folder under `pki`.
transport::ParticipantConfig dds_config(Variant v, int domain, const std::string& name, const std::string& pki,
                                        const std::string& identity);

// ---------------------------------------------------------------------------------------------
// the sample and its size on the wire (sample.cpp)

/// The leader's state as the real leader would send it: `joints` joints in all four sequences.
msg::JointState make_sample(const std::string& source, size_t joints);

/// The CDR bytes of one sample (4-byte encapsulation included), as Fast DDS serializes it.
std::vector<unsigned char> serialize(msg::JointState sample);

/// The upper bound the type's size provider gives for a sample's serialized size.
uint32_t serialized_size_bound(msg::JointState sample);

/// The header source of this pinger's samples, so that it recognises its own replies.
std::string session_source();

// ---------------------------------------------------------------------------------------------
// CPU accounting (cpu_time.cpp)

/// CPU time (user + system, all threads) of this process.
int64_t own_cpu_ns();

/// CPU time (user + system) of another process from /proc/<pid>/stat; -1 when unreadable.
int64_t process_cpu_ns(pid_t pid);

}  // namespace teleop::bench
