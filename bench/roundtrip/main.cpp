// teleop_roundtrip_bench: the command line, then the pinger's or the echo's role (see
// roundtrip.h for what the benchmark measures and how).

#include <sys/prctl.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "roundtrip.h"

namespace {

using teleop::bench::Options;

void add_public_options(CLI::App& app, Options& opt) {
  app.add_option("-n,--samples", opt.samples, "measured round trips per variant")
      ->check(CLI::Range(uint64_t{1}, uint64_t{10'000'000}))
      ->capture_default_str();
  app.add_option("--rate-hz", opt.rate_hz, "send rate (absolute deadlines)")
      ->check(CLI::Range(1.0, 100'000.0))
      ->capture_default_str();
  app.add_option("--domain", opt.domain, "DDS domain id (away from a running demo's)")
      ->check(CLI::Range(0, 232))
      ->capture_default_str();
  app.add_option("--variants", opt.variants,
                 "comma-separated variants in the order to run: raw-udp, fastdds (bare Fast DDS), dds-udp (teleop "
                 "stream preset), dds-imp (teleop with a transparent impairment layer), dds-shm, dds-sec (needs --pki), "
                 "ddsperf (Cyclone's ddsperf, if installed); all = every one that can run here")
      ->capture_default_str();
  app.add_option("--joints", opt.joints, "joints per sample (each of the 4 sequences)")
      ->check(CLI::Range(size_t{1}, size_t{1000}))
      ->capture_default_str();
  app.add_option("--topics", opt.topics, "topics published per cycle, each echoed on its own topic")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--warmup", opt.warmup, "round trips sent and discarded before measuring (after matching)")
      ->capture_default_str();
  app.add_option("--csv", opt.csv, "write every measured round trip to this CSV file");
  app.add_option("--summary-csv", opt.summary_csv,
                 "append one line per variant (percentiles, CPU, the run's parameters) to this CSV file");
  app.add_option("--pki", opt.pki,
                 "also run dds-udp with DDS Security, identities from this folder (scripts/make_pki.sh DIR "
                 "--bench-identity)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--timeout", opt.timeout_s, "seconds the echo may take to start, match and first reply")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
}

// internal: how the benchmark starts its echo processes (hidden from --help)
void add_echo_options(CLI::App& app, Options& opt) {
  app.add_option("--role", opt.role)->check(CLI::IsMember({"ping", "echo"}))->group("");
  app.add_option("--variant", opt.variant)->group("");
  app.add_option("--ready-fd", opt.ready_fd)->group("");
  app.add_option("--max-seconds", opt.max_seconds)->group("");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Round-trip latency and CPU leader -> follower -> leader of a JointState, layer by layer in one run: raw UDP, "
      "bare Fast DDS, the teleop transport (UDP, with a transparent impairment layer, shared memory) and ddsperf",
      "teleop_roundtrip_bench"};
  Options opt;
  add_public_options(app, opt);
  add_echo_options(app, opt);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  teleop::bench::install_signal_handlers();
  // wake up at the deadline, not up to 50 us later (the kernel's default timer slack)
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  try {
    return opt.role == "echo" ? teleop::bench::run_echo(opt) : teleop::bench::run_pinger(opt);
  } catch (const teleop::bench::Interrupted&) {
    std::fprintf(stderr, "teleop_roundtrip_bench: interrupted\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_roundtrip_bench%s: error: %s\n", opt.role == "echo" ? " (echo)" : "", e.what());
    return 1;
  }
}
