// The pinger's role: runs the variants one after the other, each with a fresh echo process,
// then reports.

#include <cinttypes>
#include <cstdio>
#include <stdexcept>

#include "pinger.h"
#include "report.h"

namespace teleop::bench {
namespace {

void print_header(const Options& opt, size_t wire_size, const std::vector<Variant>& variants) {
  const uint32_t size_bound = serialized_size_bound(make_sample(session_source(), opt.joints));
  std::printf("teleop_roundtrip_bench: %" PRIu64 " samples (+%" PRIu64 " warm-up) at %.0f Hz on %d topic%s, DDS domain %d\n",
              opt.samples, opt.warmup, opt.rate_hz, opt.topics, opt.topics == 1 ? "" : "s", opt.domain);
  std::printf(
      "payload: msg::JointState, %zu joints x 4 sequences = %zu bytes serialized (CDR incl. 4-byte "
      "encapsulation; the type's size provider bounds it at %u); raw UDP datagrams carry %zu bytes\n",
      opt.joints, wire_size, size_bound, wire_size);
  std::printf("variants:");
  for (Variant v : variants) std::printf(" %s", name_of(v));
  if (opt.variants == "all" && !ddsperf_available()) std::printf("   (ddsperf not installed: apt-get install cyclonedds-tools)");
  std::printf("\n1-minute load average at start: %.2f\n", load_average_1min());
}

VariantResult run_variant(Variant v, const Options& opt, const std::vector<unsigned char>& wire) {
  switch (v) {
    case Variant::kRawUdp:
      return run_raw_udp_variant(opt, wire.size(), wire);
    case Variant::kBareDds:
      return run_bare_dds_variant(opt);
    case Variant::kDdsPerf:
      return run_ddsperf_variant(opt, wire.size());
    default:
      return run_dds_variant(v, opt);
  }
}

}  // namespace

int run_pinger(const Options& opt) {
  const std::vector<Variant> variants = selected_variants(opt);
  if (opt.topics > 1 && !opt.pki.empty()) {
    throw std::invalid_argument("--topics > 1 and --pki: the permissions name only the one leader/follower pair");
  }
  const auto wire = serialize(make_sample(session_source(), opt.joints));
  print_header(opt, wire.size(), variants);
  if (wire.size() < 28) throw std::runtime_error("serialized sample too small for the raw UDP header");

  std::vector<VariantResult> results;
  for (Variant v : variants) {
    std::printf("running %s ...\n", name_of(v));
    std::fflush(stdout);
    results.push_back(run_variant(v, opt, wire));
    results.back().load_average = load_average_1min();
  }
  print_results(results);
  if (!opt.csv.empty()) {
    write_csv(opt.csv, results);
    std::printf("\nper-sample RTTs written to %s\n", opt.csv.c_str());
  }
  if (!opt.summary_csv.empty()) append_summary_csv(opt.summary_csv, opt, wire.size(), results);
  return 0;
}

}  // namespace teleop::bench
