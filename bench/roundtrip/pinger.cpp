// The pinger's role: runs the variants one after the other, each with a fresh echo process,
// then reports.

#include <cinttypes>
#include <cstdio>
#include <stdexcept>

#include "pinger.h"
#include "report.h"

namespace teleop::bench {
namespace {

/// The teleop variants --transport and --pki ask for, then the raw UDP reference, which always runs.
std::vector<Variant> selected_variants(const Options& opt) {
  std::vector<Variant> variants;
  if (opt.transport == "udp" || opt.transport == "both") variants.push_back(Variant::kDdsUdp);
  if (opt.transport == "shm" || opt.transport == "both") variants.push_back(Variant::kDdsShm);
  if (!opt.pki.empty()) variants.push_back(Variant::kDdsSecure);
  variants.push_back(Variant::kRawUdp);
  return variants;
}

void print_header(const Options& opt, size_t wire_size) {
  const uint32_t size_bound = serialized_size_bound(make_sample(session_source()));
  std::printf("teleop_roundtrip_bench: %" PRIu64 " samples (+%" PRIu64 " warm-up) at %.0f Hz, DDS domain %d\n",
              opt.samples, opt.warmup, opt.rate_hz, opt.domain);
  std::printf(
      "payload: msg::JointState, %zu joints x 4 sequences = %zu bytes serialized (CDR incl. 4-byte "
      "encapsulation; the type's size provider bounds it at %u); raw UDP datagrams carry %zu bytes\n",
      kJoints, wire_size, size_bound, wire_size);
}

}  // namespace

int run_pinger(const Options& opt) {
  const auto wire = serialize(make_sample(session_source()));
  print_header(opt, wire.size());
  if (wire.size() < 24) throw std::runtime_error("serialized sample too small for the raw UDP header");

  std::vector<VariantResult> results;
  for (Variant v : selected_variants(opt)) {
    std::printf("running %s ...\n", name_of(v));
    std::fflush(stdout);
    results.push_back(v == Variant::kRawUdp ? run_raw_udp_variant(opt, wire.size(), wire) : run_dds_variant(v, opt));
  }
  print_results(results);
  if (!opt.csv.empty()) {
    write_csv(opt.csv, results);
    std::printf("\nper-sample RTTs written to %s\n", opt.csv.c_str());
  }
  return 0;
}

}  // namespace teleop::bench
