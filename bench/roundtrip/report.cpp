#include "report.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace teleop::bench {
namespace {

double us(int64_t ns) { return static_cast<double>(ns) / 1e3; }

/// CPU time of pinger and echo together per round trip [us]; negative when unknown.
double cpu_us_per_round_trip(const VariantResult& r) {
  if (r.cpu_echo_ns < 0 || r.sent == 0) return -1;
  return us(r.cpu_ping_ns + r.cpu_echo_ns) / static_cast<double>(r.sent);
}

const VariantResult* find(const std::vector<VariantResult>& results, Variant v) {
  for (const auto& r : results) {
    if (r.variant == v && r.rtt.received > 0) return &r;
  }
  return nullptr;
}

/// Percentile `f` of `a`'s RTTs over the same percentile of `b`'s.
double percentile_ratio(const VariantResult& a, const VariantResult& b, double f) {
  return static_cast<double>(a.rtt.histogram.percentile_ns(f)) / static_cast<double>(b.rtt.histogram.percentile_ns(f));
}

void print_row(const VariantResult& r) {
  const auto& h = r.rtt.histogram;
  std::printf("%-8s %8" PRIu64 " %6" PRIu64 " %9.1f %9.1f %9.1f %9.1f %9.1f %10.1f   overruns %" PRIu64
              ", skipped %" PRIu64 ", lateness p99 %.1f us\n",
              name_of(r.variant), r.sent, r.sent - r.rtt.received, us(h.percentile_ns(0.50)), us(h.percentile_ns(0.90)),
              us(h.percentile_ns(0.99)), us(h.max_ns()), us(h.min_ns()), cpu_us_per_round_trip(r), r.overruns,
              r.skipped, us(r.lateness.percentile_ns(0.99)));
  if (r.send_failed || r.rtt.duplicates || r.rtt.stray) {
    std::printf("         (send refused %" PRIu64 ", duplicate replies %" PRIu64 ", foreign replies ignored %" PRIu64
                ")\n",
                r.send_failed, r.rtt.duplicates, r.rtt.stray);
  }
}

/// The raw UDP reference, if it got replies; nullptr otherwise.
const VariantResult* raw_reference(const std::vector<VariantResult>& results) {
  const VariantResult* raw = nullptr;
  for (const auto& r : results) {
    if (r.variant == Variant::kRawUdp) raw = &r;
  }
  return raw != nullptr && raw->rtt.received > 0 ? raw : nullptr;
}

// teleop vs raw UDP, in this run: what the middleware costs
void print_raw_ratio(const std::vector<VariantResult>& results, const VariantResult& raw) {
  std::printf("\nratio teleop/raw (same run):\n");
  for (const auto& r : results) {
    if (r.variant == Variant::kRawUdp || r.rtt.received == 0) continue;
    std::printf("  %-8s p50 %5.2fx   p99 %5.2fx\n", name_of(r.variant), percentile_ratio(r, raw, 0.50),
                percentile_ratio(r, raw, 0.99));
  }
}

// security on vs off, both over UDP in this run: latency percentiles and CPU per round trip
void print_security_ratio(const std::vector<VariantResult>& results) {
  const VariantResult* plain = find(results, Variant::kDdsUdp);
  const VariantResult* secure = find(results, Variant::kDdsSecure);
  if (plain == nullptr || secure == nullptr) return;
  std::printf("\nratio security on/off (dds-sec / dds-udp, same run):\n  p50 %5.2fx   p99 %5.2fx",
              percentile_ratio(*secure, *plain, 0.50), percentile_ratio(*secure, *plain, 0.99));
  if (cpu_us_per_round_trip(*plain) > 0 && cpu_us_per_round_trip(*secure) > 0) {
    std::printf("   cpu per round trip %5.2fx", cpu_us_per_round_trip(*secure) / cpu_us_per_round_trip(*plain));
  }
  std::printf("\n");
}

}  // namespace

void print_results(const std::vector<VariantResult>& results) {
  std::printf("\n%-8s %8s %6s %9s %9s %9s %9s %9s %10s   %s\n", "variant", "samples", "lost", "p50_us", "p90_us",
              "p99_us", "max_us", "min_us", "cpu_us/rt", "pacer (measured window)");
  for (const auto& r : results) print_row(r);
  const VariantResult* raw = raw_reference(results);
  if (raw == nullptr) return;  // no ratios at all without the reference's replies
  print_raw_ratio(results, *raw);
  print_security_ratio(results);
}

void write_csv(const std::string& path, const std::vector<VariantResult>& results) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "variant,index,seq,rtt_ns\n";
  for (const auto& r : results) {
    for (size_t i = 0; i < r.rtt.rtt_ns.size(); ++i) {
      out << name_of(r.variant) << ',' << i << ',' << r.window_begin + i << ',';
      if (r.rtt.rtt_ns[i] >= 0) out << r.rtt.rtt_ns[i];  // empty: lost
      out << '\n';
    }
  }
  if (!out) throw std::runtime_error("error writing " + path);
}

}  // namespace teleop::bench
