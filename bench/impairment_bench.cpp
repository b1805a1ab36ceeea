// teleop_impairment_bench: does the impairing transport do what its profile says, over real
// Fast DDS? Two participants in this process (intra-process delivery is off, so every sample
// crosses the loopback UDP socket through the chaining transport): the sender's egress is
// impaired, the receiver records every sample's sequence number and one-way delay (DDS reception
// time minus the sender's stamp, same host, same clock). Exact percentiles from all samples.
//
//   1. delay: 17.5 ms constant one way at 1 kHz -> median and p99 against the configuration
//   2. loss: Bernoulli 1 %, 5 %, 20 % over >= 100k samples -> measured rate, relative error
//   3. bursts: Gilbert-Elliott p = 1 %, r = 25 % -> mean burst length against 1/r = 4
//   4. overhead: round trip with the chaining layer configured but transparent, against plain
//      UDP participants, alternating in the same run
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "teleop/common/clock.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/publication.h"

namespace {

using namespace teleop;
using transport::impairment::LinkPhase;
using transport::impairment::LinkProfile;
using transport::impairment::LossModel;

const transport::TopicSpec<msg::JointState> kForward{"teleop/bench/forward", transport::QosPreset::kStream};
const transport::TopicSpec<msg::JointState> kBack{"teleop/bench/back", transport::QosPreset::kStream};

transport::ParticipantConfig config(int domain, const std::string& name, const LinkProfile* profile, uint64_t seed) {
  transport::ParticipantConfig c;
  c.domain_id = domain;
  c.name = name;
  c.udpv4 = true;
  c.shm = false;
  c.interface_whitelist = {"127.0.0.1"};
  if (profile != nullptr) {
    c.impairment.seed = seed;
    c.impairment.links.push_back({transport::impairment::kAnyPeer, *profile});
  }
  return c;
}

LinkProfile profile_of(const std::string& name, const LinkPhase& phase) {
  LinkProfile p;
  p.name = name;
  p.phases = {phase};
  return p;
}

void presize(msg::JointState& s) { transport::presize_joint_state(s, 7); }

bool wait_matched(const std::function<bool()>& matched) {
  for (int i = 0; i < 10'000 && !matched(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return matched();
}

double percentile(std::vector<int64_t> v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1);
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return static_cast<double>(v[k]);
}

// what the receiver saw of one stream
struct Reception {
  std::mutex mutex;
  std::vector<uint64_t> seqs;
  std::vector<int64_t> delays_ns;
};

// streams `count` samples at `rate_hz` from an impaired sender to a plain receiver
void stream(int domain, const LinkProfile& profile, uint64_t seed, uint64_t count, double rate_hz, Reception& rx) {
  rx.seqs.reserve(count);
  rx.delays_ns.reserve(count);
  transport::Participant receiver(config(domain, "bench_rx", nullptr, 0));
  auto reader = receiver.make_reader(kForward, std::function<void(const msg::JointState&)>([&](const msg::JointState& s) {
    const int64_t delay = system_now_ns() - s.header().stamp_ns();
    std::lock_guard lock(rx.mutex);
    rx.seqs.push_back(s.header().seq());
    rx.delays_ns.push_back(delay);
  }));
  transport::Participant sender(config(domain, "bench_tx", &profile, seed));
  transport::Publication<msg::JointState> pub(sender, kForward, "bench_tx");
  presize(pub.sample());
  if (!wait_matched([&] { return pub.matched() > 0 && reader.matched() > 0; })) throw std::runtime_error("no match");
  MonotonicClock clock;
  RatePacer pacer(clock, static_cast<int64_t>(1e9 / rate_hz));
  for (uint64_t i = 0; i < count; ++i) {
    pacer.wait_next();
    pub.publish();
  }
  // let the last delayed samples arrive
  std::this_thread::sleep_for(std::chrono::milliseconds(200) + std::chrono::nanoseconds(profile.phases[0].delay_ns * 2));
}

// loss rate and mean burst of missing sequence numbers in [1, count]
void losses(Reception& rx, uint64_t count, double& rate, double& mean_burst) {
  std::vector<bool> got(count + 1, false);
  for (uint64_t s : rx.seqs) {
    if (s >= 1 && s <= count) got[s] = true;
  }
  uint64_t missing = 0, bursts = 0;
  for (uint64_t s = 1; s <= count; ++s) {
    if (got[s]) continue;
    ++missing;
    if (s == 1 || got[s - 1]) ++bursts;
  }
  rate = static_cast<double>(missing) / static_cast<double>(count);
  mean_burst = bursts ? static_cast<double>(missing) / static_cast<double>(bursts) : 0.0;
}

void bench_delay(int domain, uint64_t count) {
  LinkPhase phase;
  phase.delay_ns = 17'500'000;
  Reception rx;
  stream(domain, profile_of("wan-35ms", phase), 1, count, 1000, rx);
  const double p50 = percentile(rx.delays_ns, 0.5) * 1e-6, p99 = percentile(rx.delays_ns, 0.99) * 1e-6;
  std::printf("delay     configured 17.500 ms one way, 1 kHz, %zu samples: p50 %.3f ms (%+.3f), p99 %.3f ms (%+.3f), "
              "max %.3f ms\n",
              rx.delays_ns.size(), p50, p50 - 17.5, p99, p99 - 17.5,
              static_cast<double>(*std::max_element(rx.delays_ns.begin(), rx.delays_ns.end())) * 1e-6);
}

void bench_loss(int domain, uint64_t count, double rate_hz) {
  for (double p : {0.01, 0.05, 0.20}) {
    LinkPhase phase;
    phase.loss = {LossModel::kBernoulli, p};
    Reception rx;
    stream(domain, profile_of("bernoulli", phase), 7, count, rate_hz, rx);
    double rate = 0, burst = 0;
    losses(rx, count, rate, burst);
    std::printf("loss      Bernoulli %4.1f %%, %lu samples at %.0f Hz: measured %.3f %% (relative error %+.1f %%)\n",
                100 * p, static_cast<unsigned long>(count), rate_hz, 100 * rate, 100 * (rate - p) / p);
  }
}

void bench_bursts(int domain, uint64_t count, double rate_hz) {
  LinkPhase phase;
  phase.loss = {LossModel::kGilbertElliott, 0, 0.01, 0.25, 1.0, 0.0};
  Reception rx;
  stream(domain, profile_of("gilbert-elliott", phase), 9, count, rate_hz, rx);
  double rate = 0, burst = 0;
  losses(rx, count, rate, burst);
  std::printf("bursts    Gilbert-Elliott p 1 %%, r 25 %%, %lu samples: loss %.3f %% (expected %.3f %%), mean burst %.2f "
              "(expected 4.00, relative error %+.1f %%)\n",
              static_cast<unsigned long>(count), 100 * rate, 100 * phase.loss.expected_loss_rate(), burst,
              100 * (burst - 4.0) / 4.0);
}

// median round trip ping -> echo -> ping, both participants chained (transparent) or plain
double round_trip_p50_us(int domain, bool chained, uint64_t count) {
  const LinkProfile transparent = profile_of("transparent", LinkPhase{});
  const LinkProfile* profile = chained ? &transparent : nullptr;
  transport::Participant echo_side(config(domain, "bench_echo", profile, 1));
  auto back = echo_side.make_writer(kBack);
  auto echo_reader = echo_side.make_reader(kForward, std::function<void(const msg::JointState&)>([&](const msg::JointState& s) {
    (void)back.write(s);
  }));
  std::vector<int64_t> rtts;
  rtts.reserve(count);
  std::mutex mutex;
  transport::Participant ping_side(config(domain, "bench_ping", profile, 2));
  auto back_reader = ping_side.make_reader(kBack, std::function<void(const msg::JointState&)>([&](const msg::JointState& s) {
    const int64_t rtt = monotonic_now_ns() - s.header().stamp_mono_ns();
    std::lock_guard lock(mutex);
    rtts.push_back(rtt);
  }));
  transport::Publication<msg::JointState> ping(ping_side, kForward, "bench_ping");
  presize(ping.sample());
  if (!wait_matched([&] { return ping.matched() > 0 && back.matched() > 0 && back_reader.matched() > 0 && echo_reader.matched() > 0; })) {
    throw std::runtime_error("round trip: no match");
  }
  MonotonicClock clock;
  RatePacer pacer(clock, kNsPerMs);
  for (uint64_t i = 0; i < count; ++i) {
    pacer.wait_next();
    ping.publish();
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::lock_guard lock(mutex);
  return percentile(rtts, 0.5) * 1e-3;
}

void bench_overhead(int domain, uint64_t count, int rounds) {
  std::vector<double> plain, chained;
  for (int r = 0; r < rounds; ++r) {
    // alternate, so that drifting machine load hits both alike
    plain.push_back(round_trip_p50_us(domain, false, count));
    chained.push_back(round_trip_p50_us(domain, true, count));
  }
  std::sort(plain.begin(), plain.end());
  std::sort(chained.begin(), chained.end());
  const double a = plain[plain.size() / 2], b = chained[chained.size() / 2];
  std::printf("overhead  round trip p50 (median of %d alternating runs of %lu): plain UDP %.1f us, chaining layer with a "
              "transparent profile %.1f us: %+.1f %%\n",
              rounds, static_cast<unsigned long>(count), a, b, 100 * (b - a) / a);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_impairment_bench: the impairing transport against its configuration, over real Fast DDS"};
  int domain = 78;
  uint64_t delay_samples = 20'000;
  uint64_t loss_samples = 100'000;
  double loss_rate_hz = 5000;
  int rounds = 5;
  std::vector<std::string> only;
  app.add_option("--domain", domain)->check(CLI::Range(0, 232));
  app.add_option("--delay-samples", delay_samples, "samples of the 17.5 ms delay run (at 1 kHz)");
  app.add_option("--loss-samples", loss_samples, "samples per loss run");
  app.add_option("--loss-rate-hz", loss_rate_hz, "publication rate of the loss runs (loss does not depend on it)");
  app.add_option("--rounds", rounds, "alternating runs of the overhead comparison");
  app.add_option("--only", only, "delay, loss, bursts, overhead (default: all)");
  CLI11_PARSE(app, argc, argv);
  auto wanted = [&](const char* what) { return only.empty() || std::find(only.begin(), only.end(), what) != only.end(); };
  try {
    if (wanted("delay")) bench_delay(domain, delay_samples);
    if (wanted("loss")) bench_loss(domain, loss_samples, loss_rate_hz);
    if (wanted("bursts")) bench_bursts(domain, loss_samples, loss_rate_hz);
    if (wanted("overhead")) bench_overhead(domain, 2000, rounds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "impairment bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
