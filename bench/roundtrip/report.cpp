#include "report.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace teleop::bench {
namespace {

double us(int64_t ns) { return ns < 0 ? -1.0 : static_cast<double>(ns) / 1e3; }

/// Samples sent in the measured window (cycles x topics).
uint64_t samples_sent(const VariantResult& r) { return r.sent * static_cast<uint64_t>(r.topics); }

/// CPU time of pinger and echo together per round trip [us]; negative when unknown.
double cpu_us_per_round_trip(const VariantResult& r) {
  const uint64_t n = r.external ? r.external->received : samples_sent(r);
  if (r.cpu_echo_ns < 0 || n == 0) return -1;
  return us(r.cpu_ping_ns + r.cpu_echo_ns) / static_cast<double>(n);
}

double side_us_per_round_trip(const VariantResult& r, int64_t cpu_ns) {
  const uint64_t n = r.external ? r.external->received : samples_sent(r);
  return cpu_ns < 0 || n == 0 ? -1.0 : us(cpu_ns) / static_cast<double>(n);
}

const VariantResult* find(const std::vector<VariantResult>& results, Variant v) {
  for (const auto& r : results) {
    if (r.variant == v && figures_of(r).received > 0) return &r;
  }
  return nullptr;
}

std::string cell(double value, const char* format) {
  if (value < 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

void print_row(const VariantResult& r) {
  const RttFigures f = figures_of(r);
  const std::string lost = r.external ? "-" : std::to_string(samples_sent(r) - f.received);
  std::printf("%-8s %8" PRIu64 " %6s %9s %9s %9s %9s %9s %9s %10s %s %5.2f",
              name_of(r.variant), r.external ? f.received : samples_sent(r), lost.c_str(),
              cell(us(f.p50_ns), "%.1f").c_str(), cell(us(f.p90_ns), "%.1f").c_str(),
              cell(us(f.p99_ns), "%.1f").c_str(), cell(us(f.p999_ns), "%.1f").c_str(),
              cell(us(f.max_ns), "%.1f").c_str(), cell(us(f.min_ns), "%.1f").c_str(),
              cell(cpu_us_per_round_trip(r), "%.1f").c_str(),
              (cell(side_us_per_round_trip(r, r.cpu_ping_ns), "%.1f") + "+" +
               cell(side_us_per_round_trip(r, r.cpu_echo_ns), "%.1f"))
                  .c_str(),
              r.load_average);
  if (!r.external) {
    std::printf("   overruns %" PRIu64 ", skipped %" PRIu64 ", lateness p99 %.1f us", r.overruns, r.skipped,
                us(r.lateness.percentile_ns(0.99)));
  }
  std::printf("\n");
  if (r.send_failed || r.rtt.duplicates || r.rtt.stray) {
    std::printf("         (send refused %" PRIu64 ", duplicate replies %" PRIu64 ", foreign replies ignored %" PRIu64
                ")\n",
                r.send_failed, r.rtt.duplicates, r.rtt.stray);
  }
}

double ratio(int64_t a, int64_t b) { return a > 0 && b > 0 ? static_cast<double>(a) / static_cast<double>(b) : -1; }

// one variant against a reference of the same run: p50, p99 and CPU per round trip
std::string ratios_text(const VariantResult& r, const VariantResult* ref) {
  if (ref == nullptr || ref == &r) return "-";
  const RttFigures a = figures_of(r);
  const RttFigures b = figures_of(*ref);
  const double cpu_a = cpu_us_per_round_trip(r);
  const double cpu_b = cpu_us_per_round_trip(*ref);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%5sx %5sx %5sx", cell(ratio(a.p50_ns, b.p50_ns), "%.2f").c_str(),
                cell(ratio(a.p99_ns, b.p99_ns), "%.2f").c_str(),
                cell(cpu_a > 0 && cpu_b > 0 ? cpu_a / cpu_b : -1, "%.2f").c_str());
  return buf;
}

// every variant against bare Fast DDS and against raw UDP, in this run: what each layer costs
void print_ratios(const std::vector<VariantResult>& results) {
  const VariantResult* bare = find(results, Variant::kBareDds);
  const VariantResult* raw = find(results, Variant::kRawUdp);
  if (bare == nullptr && raw == nullptr) return;
  std::printf("\nratios, same run (p50, p99, cpu per round trip):\n");
  std::printf("  %-8s %-22s %-22s\n", "variant", "/ fastdds", "/ raw-udp");
  for (const auto& r : results) {
    if (r.variant == Variant::kRawUdp || figures_of(r).received == 0) continue;
    std::printf("  %-8s %-22s %-22s\n", name_of(r.variant), ratios_text(r, bare).c_str(), ratios_text(r, raw).c_str());
  }
}

// security on vs off, both over UDP in this run: latency percentiles and CPU per round trip
void print_security_ratio(const std::vector<VariantResult>& results) {
  const VariantResult* plain = find(results, Variant::kDdsUdp);
  const VariantResult* secure = find(results, Variant::kDdsSecure);
  if (plain == nullptr || secure == nullptr) return;
  std::printf("\nratio security on/off (dds-sec / dds-udp, same run): %s\n", ratios_text(*secure, plain).c_str());
}

}  // namespace

RttFigures figures_of(const VariantResult& r) {
  if (r.external) return *r.external;
  const auto& h = r.rtt.histogram;
  RttFigures f;
  f.received = r.rtt.received;
  if (f.received == 0) return f;
  f.p50_ns = h.percentile_ns(0.50);
  f.p90_ns = h.percentile_ns(0.90);
  f.p99_ns = h.percentile_ns(0.99);
  f.p999_ns = h.percentile_ns(0.999);
  f.max_ns = h.max_ns();
  f.min_ns = h.min_ns();
  return f;
}

void print_results(const std::vector<VariantResult>& results) {
  std::printf("\n%-8s %8s %6s %9s %9s %9s %9s %9s %9s %10s %-11s %5s   %s\n", "variant", "samples", "lost", "p50_us",
              "p90_us", "p99_us", "p99.9_us", "max_us", "min_us", "cpu_us/rt", "(ping+echo)", "load",
              "pacer (measured window)");
  for (const auto& r : results) print_row(r);
  print_ratios(results);
  print_security_ratio(results);
}

void write_csv(const std::string& path, const std::vector<VariantResult>& results) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "variant,index,seq,topic,rtt_ns\n";
  for (const auto& r : results) {
    const auto topics = static_cast<size_t>(r.topics);
    for (size_t i = 0; i < r.rtt.rtt_ns.size(); ++i) {
      out << name_of(r.variant) << ',' << i / topics << ',' << r.window_begin + i / topics << ',' << i % topics << ',';
      if (r.rtt.rtt_ns[i] >= 0) out << r.rtt.rtt_ns[i];  // empty: lost
      out << '\n';
    }
  }
  if (!out) throw std::runtime_error("error writing " + path);
}

void append_summary_csv(const std::string& path, const Options& opt, size_t payload_bytes,
                        const std::vector<VariantResult>& results) {
  const bool fresh = !std::ifstream(path).good();
  std::ofstream out(path, std::ios::app);
  if (!out) throw std::runtime_error("cannot write " + path);
  if (fresh) {
    out << "variant,joints,payload_bytes,topics,rate_hz,samples,received,p50_us,p90_us,p99_us,p999_us,max_us,min_us,"
           "cpu_us_per_rt,cpu_ping_us_per_rt,cpu_echo_us_per_rt,load1\n";
  }
  for (const auto& r : results) {
    const RttFigures f = figures_of(r);
    out << name_of(r.variant) << ',' << opt.joints << ',' << payload_bytes << ',' << r.topics << ',' << opt.rate_hz
        << ',' << (r.external ? f.received : samples_sent(r)) << ',' << f.received << ',' << us(f.p50_ns) << ','
        << us(f.p90_ns) << ',' << us(f.p99_ns) << ',' << us(f.p999_ns) << ',' << us(f.max_ns) << ','
        << us(f.min_ns) << ',' << cpu_us_per_round_trip(r) << ',' << side_us_per_round_trip(r, r.cpu_ping_ns) << ','
        << side_us_per_round_trip(r, r.cpu_echo_ns) << ',' << r.load_average << '\n';
  }
  if (!out) throw std::runtime_error("error writing " + path);
}

}  // namespace teleop::bench
