// teleop_link_probe: one end of a test link between two processes. The publisher streams
// JointState samples (optionally through an impairment profile); the subscriber records what
// arrived and when the publisher's liveliness came and went, and writes a node report.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace {

using namespace teleop;

struct Options {
  std::string role;
  std::string name = "probe";
  int domain = 0;
  std::string qos = "stream";
  double rate_hz = 1000;
  uint64_t count = 1000;
  double duration_s = 10;
  double linger_s = 1;
  std::string profile;
  uint64_t seed = 1;
  int64_t lease_ms = 500;
  bool exclude_discovery = false;
  bool idle_exit = false;
  std::string report;
};

transport::ParticipantConfig participant_config(const Options& o) {
  transport::ParticipantConfig c;
  c.domain_id = o.domain;
  c.name = o.name;
  c.udpv4 = true;
  c.shm = false;
  c.interface_whitelist = {"127.0.0.1"};
  c.liveliness_lease_ns = o.lease_ms * kNsPerMs;
  // long enough that a test outage does not also remove the whole participant
  c.participant_lease_ns = 20 * kNsPerS;
  if (!o.profile.empty()) {
    c.impairment.seed = o.seed;
    c.impairment.exclude_discovery = o.exclude_discovery;
    c.impairment.links.push_back({transport::impairment::kAnyPeer, transport::impairment::load_link_profile(o.profile)});
  }
  return c;
}

transport::TopicSpec<msg::JointState> topic(const Options& o) {
  return {"teleop/test/probe", o.qos == "event" ? transport::QosPreset::kEvent : transport::QosPreset::kStream};
}

bool wait_until(const std::function<bool()>& condition, double timeout_s) {
  const int64_t until = monotonic_now_ns() + static_cast<int64_t>(timeout_s * 1e9);
  while (!condition()) {
    if (monotonic_now_ns() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

int publish(const Options& o) {
  transport::Participant participant(participant_config(o));
  transport::Publication<msg::JointState> pub(participant, topic(o), o.name);
  transport::presize_joint_state(pub.sample(), 7);
  if (!wait_until([&] { return pub.matched() > 0; }, 20)) {
    std::fprintf(stderr, "probe %s: no subscriber matched within 20 s\n", o.name.c_str());
    return 1;
  }
  MonotonicClock clock;
  RatePacer pacer(clock, static_cast<int64_t>(1e9 / o.rate_hz));
  for (uint64_t i = 0; i < o.count; ++i) {
    pacer.wait_next();
    pub.sample().q_rad()[0] = static_cast<double>(i);
    pub.publish();
  }
  // stay up so that reliable repairs and delayed messages still go out
  std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int64_t>(o.linger_s * 1e3)));
  std::printf("probe %s: published %lu samples, %lu refused\n", o.name.c_str(), static_cast<unsigned long>(pub.sent()),
              static_cast<unsigned long>(pub.failed()));
  if (!o.report.empty()) {
    runtime::NodeReport r;
    r.name = o.name;
    r.role = "probe_pub";
    r.final_state = "done";
    r.add(pub);
    r.add_links(participant);
    // a stalled loop drops deadlines: those samples were never sent, so no gap can show them
    r.counters.emplace_back("skipped_cycles", static_cast<double>(pacer.stats().skipped));
    runtime::write_report(r, o.report);
  }
  return 0;
}

int subscribe(const Options& o) {
  transport::Participant participant(participant_config(o));
  transport::Subscription<msg::JointState> sub(participant, topic(o));
  MonotonicClock clock;
  RatePacer pacer(clock, kNsPerMs);
  const int64_t end = monotonic_now_ns() + static_cast<int64_t>(o.duration_s * 1e9);
  int32_t max_alive = 0;
  while (monotonic_now_ns() < end) {
    pacer.wait_next();
    sub.poll();
    max_alive = std::max(max_alive, sub.reader().alive_writers());
    // done early once the last sample arrived, or the stream has been silent for a second
    if (sub.has_sample() && sub.latest().header().seq() >= o.count) break;
    if (sub.has_sample() && sub.age_ns(monotonic_now_ns()) > kNsPerS && o.idle_exit) break;
  }
  std::printf("probe %s: received %lu, liveliness lost %lu times\n", o.name.c_str(),
              static_cast<unsigned long>(sub.stats().received()), static_cast<unsigned long>(sub.reader().liveliness_lost()));
  if (!o.report.empty()) {
    runtime::NodeReport r;
    r.name = o.name;
    r.role = "probe_sub";
    r.final_state = "done";
    r.add(sub);
    r.counters.emplace_back("max_alive_writers", max_alive);
    r.counters.emplace_back("alive_writers_at_end", sub.reader().alive_writers());
    runtime::write_report(r, o.report);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"teleop_link_probe: one end of a test link"};
  app.add_option("--role", o.role, "pub or sub")->required()->check(CLI::IsMember({"pub", "sub"}));
  app.add_option("--name", o.name, "participant name");
  app.add_option("--domain", o.domain)->check(CLI::Range(0, 232));
  app.add_option("--qos", o.qos, "stream or event")->check(CLI::IsMember({"stream", "event"}));
  app.add_option("--rate-hz", o.rate_hz)->check(CLI::Range(1.0, 10000.0));
  app.add_option("--count", o.count, "samples to publish / the last sequence number to wait for");
  app.add_option("--duration", o.duration_s, "subscriber: longest run time [s]");
  app.add_option("--linger", o.linger_s, "publisher: time to stay up after the last sample [s]");
  app.add_option("--profile", o.profile, "impairment profile file for every outgoing link")->check(CLI::ExistingFile);
  app.add_option("--seed", o.seed);
  app.add_flag("--idle-exit", o.idle_exit, "subscriber: stop after 1 s without samples (once some came)");
  app.add_flag("--exclude-discovery", o.exclude_discovery, "leave discovery traffic unimpaired");
  app.add_option("--lease-ms", o.lease_ms, "liveliness lease");
  app.add_option("--report", o.report, "write a node report here");
  CLI11_PARSE(app, argc, argv);
  try {
    return o.role == "pub" ? publish(o) : subscribe(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe %s: %s\n", o.name.c_str(), e.what());
    return 1;
  }
}
