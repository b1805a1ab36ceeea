// The echo role (`--role echo`, started by the pinger through EchoProcess): sends every sample of
// its variant straight back unchanged until SIGTERM, its parent's death or --max-seconds.

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <memory>

#include "bare_dds.h"
#include "loopback_udp.h"
#include "profile_window.h"
#include "roundtrip.h"
#include "teleop/common/clock.h"
#include "teleop/transport/participant.h"

namespace teleop::bench {
namespace {

using msg::JointState;

/// True while the echo should keep running.
bool echo_should_run(pid_t parent, int64_t end_mono_ns) {
  return !stop_requested() && getppid() == parent && monotonic_now_ns() < end_mono_ns;
}

void announce_ready(int fd, const std::string& what) {
  const std::string line = "ready" + what + "\n";
  if (write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
    throw std::runtime_error("could not tell the pinger that the echo is ready");
  }
  close(fd);
}

/// What the echo sent back, and the profile window: opened once the warm-up went through (the
/// pinger's measured window starts after it), closed when the echo is told to stop.
class EchoCount {
 public:
  explicit EchoCount(uint64_t warmup_samples) : warmup_(warmup_samples) {}
  void on_echo(bool ok) {
    if (!ok) {
      refused_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    const uint64_t n = echoed_.fetch_add(1, std::memory_order_relaxed) + 1;
    if (n == warmup_) {
      profile_window_open();
      at_open_.store(n, std::memory_order_relaxed);
    }
  }
  void finish(Variant v) {
    profile_window_close();
    const uint64_t echoed = echoed_.load();
    std::fprintf(stderr, "echo %s: %" PRIu64 " echoed (%" PRIu64 " after the warm-up), %" PRIu64 " refused\n",
                 name_of(v), echoed, echoed - at_open_.load(), refused_.load());
  }

 private:
  const uint64_t warmup_;
  std::atomic<uint64_t> echoed_{0};
  std::atomic<uint64_t> refused_{0};
  std::atomic<uint64_t> at_open_{0};
};

int run_dds_echo(Variant v, const Options& opt, pid_t parent, int64_t end_mono_ns) {
  const TopicNames names = topic_names(opt.topics);
  EchoCount count(opt.warmup * static_cast<uint64_t>(opt.topics));
  transport::Participant participant(dds_config(v, opt.domain, "teleop_bench_echo", opt.pki, "bench_echo"));
  // raw writers, not Publications: the sample goes back with the pinger's header untouched
  std::vector<transport::Writer<JointState>> writers;
  std::vector<transport::Reader<JointState>> readers;
  for (const auto& pong : names.pong) {
    writers.push_back(participant.make_writer(transport::TopicSpec<JointState>{pong.c_str(), transport::QosPreset::kStream}));
  }
  for (size_t i = 0; i < names.ping.size(); ++i) {
    readers.push_back(participant.make_reader<JointState>(
        transport::TopicSpec<JointState>{names.ping[i].c_str(), transport::QosPreset::kStream},
        [writer = writers[i], &count](const JointState& sample) mutable { count.on_echo(writer.write(sample)); }));
  }
  announce_ready(opt.ready_fd, "");
  while (echo_should_run(parent, end_mono_ns)) usleep(20'000);
  count.finish(v);
  return 0;
}

int run_bare_dds_echo(const Options& opt, pid_t parent, int64_t end_mono_ns) {
  const TopicNames names = topic_names(opt.topics);
  EchoCount count(opt.warmup * static_cast<uint64_t>(opt.topics));
  // the listener runs inside the constructor's readers: reach the endpoints through a pointer
  // set once they all exist
  std::atomic<BareDds*> self{nullptr};
  BareDds dds(opt.domain, names.pong, names.ping, [&self, &count](int topic, JointState& sample) {
    if (BareDds* d = self.load(std::memory_order_acquire)) count.on_echo(d->write(topic, sample));
  });
  self.store(&dds, std::memory_order_release);
  announce_ready(opt.ready_fd, "");
  while (echo_should_run(parent, end_mono_ns)) usleep(20'000);
  count.finish(Variant::kBareDds);
  return 0;
}

int run_udp_echo(const Options& opt, pid_t parent, int64_t end_mono_ns) {
  FdGuard sock{loopback_udp_socket(0)};
  EchoCount count(opt.warmup * static_cast<uint64_t>(opt.topics));
  announce_ready(opt.ready_fd, " " + std::to_string(local_port(sock.fd)));
  std::vector<unsigned char> buf(65536);
  while (echo_should_run(parent, end_mono_ns)) {
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = recvfrom(sock.fd, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &len);
    if (n <= 0) continue;  // timeout slice or EINTR
    count.on_echo(sendto(sock.fd, buf.data(), static_cast<size_t>(n), 0, reinterpret_cast<sockaddr*>(&from), len) == n);
  }
  count.finish(Variant::kRawUdp);
  return 0;
}

}  // namespace

int run_echo(const Options& opt) {
  const auto v = parse_variant(opt.variant);
  if (!v || *v == Variant::kDdsPerf) {
    std::fprintf(stderr, "echo: unknown --variant '%s'\n", opt.variant.c_str());
    return 2;
  }
  if (opt.ready_fd < 0) {
    std::fprintf(stderr, "echo: --ready-fd missing (the echo role is started by the benchmark itself)\n");
    return 2;
  }
  const pid_t parent = getppid();
  const int64_t end = monotonic_now_ns() + static_cast<int64_t>(opt.max_seconds * 1e9);
  if (*v == Variant::kRawUdp) return run_udp_echo(opt, parent, end);
  if (*v == Variant::kBareDds) return run_bare_dds_echo(opt, parent, end);
  return run_dds_echo(*v, opt, parent, end);
}

}  // namespace teleop::bench
