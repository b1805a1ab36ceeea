// The echo role (`--role echo`, started by the pinger through EchoProcess): sends every sample of
// its variant straight back unchanged until SIGTERM, its parent's death or --max-seconds.

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cinttypes>
#include <cstdio>

#include "loopback_udp.h"
#include "roundtrip.h"
#include "teleop/common/clock.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/topics.h"

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

int run_dds_echo(Variant v, const Options& opt, pid_t parent, int64_t end_mono_ns) {
  transport::Participant participant(dds_config(v, opt.domain, "teleop_bench_echo", opt.pki, "bench_echo"));
  // raw writer, not Publication: the sample goes back with the pinger's header untouched
  transport::Writer<JointState> writer = participant.make_writer(transport::topics::kFollowerState);
  std::atomic<uint64_t> echoed{0};
  std::atomic<uint64_t> refused{0};
  auto reader = participant.make_reader<JointState>(transport::topics::kLeaderState,
                                                    [writer, &echoed, &refused](const JointState& sample) mutable {
                                                      if (writer.write(sample)) {
                                                        echoed.fetch_add(1, std::memory_order_relaxed);
                                                      } else {
                                                        refused.fetch_add(1, std::memory_order_relaxed);
                                                      }
                                                    });
  announce_ready(opt.ready_fd, "");
  while (echo_should_run(parent, end_mono_ns)) usleep(20'000);
  if (refused.load() > 0) {
    std::fprintf(stderr, "echo %s: %" PRIu64 " echoed, %" PRIu64 " refused by DDS\n", name_of(v), echoed.load(),
                 refused.load());
  }
  (void)reader;
  return 0;
}

int run_udp_echo(const Options& opt, pid_t parent, int64_t end_mono_ns) {
  FdGuard sock{loopback_udp_socket(0)};
  announce_ready(opt.ready_fd, " " + std::to_string(local_port(sock.fd)));
  std::vector<unsigned char> buf(65536);
  while (echo_should_run(parent, end_mono_ns)) {
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = recvfrom(sock.fd, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &len);
    if (n <= 0) continue;  // timeout slice or EINTR
    sendto(sock.fd, buf.data(), static_cast<size_t>(n), 0, reinterpret_cast<sockaddr*>(&from), len);
  }
  return 0;
}

}  // namespace

int run_echo(const Options& opt) {
  const auto v = parse_variant(opt.variant);
  if (!v) {
    std::fprintf(stderr, "echo: unknown --variant '%s'\n", opt.variant.c_str());
    return 2;
  }
  if (opt.ready_fd < 0) {
    std::fprintf(stderr, "echo: --ready-fd missing (the echo role is started by the benchmark itself)\n");
    return 2;
  }
  const pid_t parent = getppid();
  const int64_t end = monotonic_now_ns() + static_cast<int64_t>(opt.max_seconds * 1e9);
  return *v == Variant::kRawUdp ? run_udp_echo(opt, parent, end) : run_dds_echo(*v, opt, parent, end);
}

}  // namespace teleop::bench
