// teleop_roundtrip_bench: leader -> follower -> leader round-trip latency of a 7-joint
// msg::JointState at a fixed rate, through the teleop transport (Fast DDS over UDP and over shared
// memory), and beside it, in the same run, a raw UDP ping-pong on 127.0.0.1 of a payload of the
// same size as the serialized sample. The ratio teleop/raw is what the middleware costs.
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

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <CLI/CLI.hpp>

#include <atomic>
#include <cerrno>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "teleop/common/clock.h"
#include "teleop/common/histogram.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/topics.h"
#include "teleop/transport/type_support.h"

namespace {

using teleop::DurationHistogram;
using teleop::kNsPerMs;
using teleop::kNsPerS;
using teleop::monotonic_now_ns;
using teleop::msg::JointState;
namespace transport = teleop::transport;

constexpr size_t kJoints = 7;

// ---------------------------------------------------------------------------------------------
// signals: SIGINT/SIGTERM only set a flag that every loop polls

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_stop_signal(int /*signo*/) { g_stop.store(true); }

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: blocking calls return EINTR and the loops see the flag
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

/// A stop signal arrived: unwind (which stops the echo) and exit 130.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

/// Seconds as a short human string ("10", "0.5").
std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

// ---------------------------------------------------------------------------------------------
// variants

enum class Variant { kDdsUdp, kDdsShm, kDdsSecure, kRawUdp };

const char* name_of(Variant v) {
  switch (v) {
    case Variant::kDdsUdp:
      return "dds-udp";
    case Variant::kDdsShm:
      return "dds-shm";
    case Variant::kDdsSecure:
      return "dds-sec";
    case Variant::kRawUdp:
      return "raw-udp";
  }
  return "?";
}

std::optional<Variant> parse_variant(const std::string& name) {
  for (Variant v : {Variant::kDdsUdp, Variant::kDdsShm, Variant::kDdsSecure, Variant::kRawUdp}) {
    if (name == name_of(v)) return v;
  }
  return std::nullopt;
}

// the secure variant's identities: the pinger is the leader (publishes leader/joint_state, reads
// follower/joint_state); the echo the reverse, which only the benchmark's own identity may do
transport::SecurityConfig bench_security(const std::string& pki, const std::string& identity) {
  transport::SecurityConfig s;
  s.identity_ca = pki + "/identity_ca.pem";
  s.identity_certificate = pki + "/" + identity + "/identity.pem";
  s.private_key = pki + "/" + identity + "/key.pem";
  s.permissions_ca = pki + "/permissions_ca.pem";
  s.governance = pki + "/governance.p7s";
  s.permissions = pki + "/" + identity + "/permissions.p7s";
  return s;
}

transport::ParticipantConfig dds_config(Variant v, int domain, const std::string& name, const std::string& pki,
                                        const std::string& identity) {
  transport::ParticipantConfig config;
  config.domain_id = domain;
  config.name = name;
  // one transport only, so that the variant measures exactly that transport (discovery included)
  config.udpv4 = v == Variant::kDdsUdp || v == Variant::kDdsSecure;
  config.shm = v == Variant::kDdsShm;
  if (v == Variant::kDdsSecure) config.security = bench_security(pki, identity);
  return config;
}

/// CPU time (user + system, all threads) of this process.
int64_t own_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec * kNsPerS + ts.tv_nsec;
}

/// CPU time (user + system) of another process from /proc/<pid>/stat; -1 when unreadable.
int64_t process_cpu_ns(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // fields after the command name (which may hold spaces) start after the last ')'
  const auto close = text.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(text.substr(close + 2));
  std::string skip;
  for (int i = 3; i < 14; ++i) fields >> skip;  // state .. cmajflt
  long long utime = 0;
  long long stime = 0;
  fields >> utime >> stime;
  if (!fields) return -1;
  return (utime + stime) * (kNsPerS / sysconf(_SC_CLK_TCK));
}

struct Options {
  // public
  uint64_t samples = 5000;
  double rate_hz = 1000.0;
  int domain = 77;
  std::string transport = "both";
  std::string pki;
  uint64_t warmup = 200;
  std::string csv;
  double timeout_s = 10.0;
  // internal: the echo process
  std::string role = "ping";
  std::string variant;
  int ready_fd = -1;
  double max_seconds = 0.0;
};

// ---------------------------------------------------------------------------------------------
// the sample and its size on the wire

/// The leader's state as the real leader would send it: 7 joints in all four sequences.
JointState make_sample(const std::string& source) {
  JointState s;
  s.header().source(source);
  s.robot("panda");
  s.arm("right");
  transport::presize_joint_state(s, kJoints);
  for (size_t i = 0; i < kJoints; ++i) {
    const double x = static_cast<double>(i + 1);
    s.q_rad()[i] = 0.1 * x;
    s.dq_radps()[i] = -0.01 * x;
    s.tau_measured_nm()[i] = 1.5 * x;
    s.tau_ext_nm()[i] = 0.05 * x;
  }
  return s;
}

/// The CDR bytes of one sample (4-byte encapsulation included), as Fast DDS serializes it.
std::vector<unsigned char> serialize(JointState sample) {
  transport::PubSubTypeOf<JointState>::type type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.m_typeSize);
  if (!type.serialize(&sample, &payload)) throw std::runtime_error("could not serialize a JointState");
  return {payload.data, payload.data + payload.length};
}

// ---------------------------------------------------------------------------------------------
// RTT bookkeeping, fed from a receive thread

class RttRecorder {
 public:
  explicit RttRecorder(uint64_t window_size) : window_size_(window_size), rtt_ns_(window_size, -1) {}

  /// Called on the receive thread with the reply's sequence number and the pinger's monotonic
  /// stamp it carries, and the monotonic time of arrival.
  void on_reply(uint64_t seq, int64_t stamp_mono_ns, int64_t arrival_mono_ns) {
    replies_.fetch_add(1, std::memory_order_release);
    const uint64_t begin = window_begin_.load(std::memory_order_acquire);
    if (seq < begin || seq - begin >= window_size_) return;  // warm-up, or not ours to measure
    const int64_t rtt = arrival_mono_ns - stamp_mono_ns;
    std::lock_guard lock(mutex_);
    int64_t& slot = rtt_ns_[seq - begin];
    if (slot >= 0) {
      ++duplicates_;
      return;
    }
    slot = rtt;
    histogram_.record(rtt);
    ++received_;
  }
  void on_stray() { stray_.fetch_add(1, std::memory_order_relaxed); }

  /// Replies of any sequence number seen so far (the echo is alive and answering).
  uint64_t replies() const { return replies_.load(std::memory_order_acquire); }
  /// From now on, sequence numbers [first_seq, first_seq + window) are measured.
  void open_window(uint64_t first_seq) { window_begin_.store(first_seq, std::memory_order_release); }
  uint64_t window_begin() const { return window_begin_.load(std::memory_order_acquire); }

  uint64_t received() const {
    std::lock_guard lock(mutex_);
    return received_;
  }

  struct Snapshot {
    DurationHistogram histogram;
    std::vector<int64_t> rtt_ns;  // per window index; -1 = no reply
    uint64_t received = 0;
    uint64_t duplicates = 0;
    uint64_t stray = 0;
  };
  Snapshot snapshot() const {
    std::lock_guard lock(mutex_);
    return {histogram_, rtt_ns_, received_, duplicates_, stray_.load(std::memory_order_relaxed)};
  }

 private:
  const uint64_t window_size_;
  std::atomic<uint64_t> window_begin_{UINT64_MAX};
  std::atomic<uint64_t> replies_{0};
  std::atomic<uint64_t> stray_{0};
  mutable std::mutex mutex_;
  DurationHistogram histogram_;
  std::vector<int64_t> rtt_ns_;
  uint64_t received_ = 0;
  uint64_t duplicates_ = 0;
};

// ---------------------------------------------------------------------------------------------
// the echo process

/// A child process running this executable with `--role echo`. Killed and reaped by the
/// destructor on every path.
class EchoProcess {
 public:
  explicit EchoProcess(const std::vector<std::string>& echo_args) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
    std::vector<std::string> args{"teleop_roundtrip_bench"};
    args.insert(args.end(), echo_args.begin(), echo_args.end());
    args.push_back("--ready-fd");
    args.push_back(std::to_string(fds[1]));
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) {
      const int err = errno;
      close(fds[0]);
      close(fds[1]);
      throw std::runtime_error(std::string("fork: ") + std::strerror(err));
    }
    if (pid_ == 0) {
      // child: async-signal-safe calls only until exec
      prctl(PR_SET_PDEATHSIG, SIGTERM);  // the echo dies with the pinger, whatever kills it
      if (getppid() != parent) _exit(127);
      fcntl(fds[1], F_SETFD, 0);  // the ready pipe survives exec
      execv("/proc/self/exe", argv.data());
      _exit(127);
    }
    close(fds[1]);
    ready_fd_ = fds[0];
  }
  ~EchoProcess() { stop(); }
  EchoProcess(const EchoProcess&) = delete;
  EchoProcess& operator=(const EchoProcess&) = delete;

  /// Waits for the echo's "ready ..." line; returns what follows "ready". Throws on timeout,
  /// on the echo's death and on a stop signal.
  std::string wait_ready(int64_t deadline_mono_ns) {
    std::string line;
    while (true) {
      if (g_stop.load()) throw Interrupted();
      const int64_t left_ms = (deadline_mono_ns - monotonic_now_ns()) / kNsPerMs;
      if (left_ms <= 0) throw std::runtime_error("the echo process did not get ready in time");
      pollfd p{ready_fd_, POLLIN, 0};
      const int n = poll(&p, 1, static_cast<int>(std::min<int64_t>(left_ms, 100)));
      if (n <= 0) continue;  // timeout slice or EINTR
      char c = 0;
      const ssize_t r = read(ready_fd_, &c, 1);
      if (r == 0) throw std::runtime_error("the echo process exited before it was ready" + exit_description());
      if (r < 0) continue;
      if (c == '\n') break;
      line.push_back(c);
    }
    if (line.rfind("ready", 0) != 0) throw std::runtime_error("unexpected message from the echo: " + line);
    return line.substr(5);
  }

  /// CPU time the echo has used so far; -1 when it cannot be read.
  int64_t cpu_ns() const { return pid_ > 0 ? process_cpu_ns(pid_) : -1; }

  /// Throws if the echo has died.
  void check_alive() {
    if (pid_ <= 0) throw std::runtime_error("the echo process is gone");
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      status_ = status;
      throw std::runtime_error("the echo process died" + exit_description());
    }
  }

  /// SIGTERM, up to 3 s to exit cleanly, then SIGKILL; always reaps.
  void stop() {
    if (ready_fd_ >= 0) {
      close(ready_fd_);
      ready_fd_ = -1;
    }
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    const int64_t give_up = monotonic_now_ns() + 3 * kNsPerS;
    int status = 0;
    while (true) {
      const pid_t r = waitpid(pid_, &status, WNOHANG);
      if (r == pid_ || (r < 0 && errno == ECHILD)) break;
      if (monotonic_now_ns() > give_up) {
        std::fprintf(stderr, "teleop_roundtrip_bench: echo %d ignored SIGTERM, killing it\n", static_cast<int>(pid_));
        kill(pid_, SIGKILL);
        while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        break;
      }
      usleep(10'000);
    }
    status_ = status;
    pid_ = -1;
  }

 private:
  std::string exit_description() {
    if (pid_ > 0) {
      int status = 0;
      // it closed its pipe: it is exiting; give it a moment to be reapable
      for (int i = 0; i < 100; ++i) {
        if (waitpid(pid_, &status, WNOHANG) == pid_) {
          pid_ = -1;
          status_ = status;
          break;
        }
        usleep(10'000);
      }
    }
    if (!status_) return "";
    if (WIFEXITED(*status_)) return " (exit status " + std::to_string(WEXITSTATUS(*status_)) + ")";
    if (WIFSIGNALED(*status_)) return " (killed by signal " + std::to_string(WTERMSIG(*status_)) + ")";
    return "";
  }

  pid_t pid_ = -1;
  int ready_fd_ = -1;
  std::optional<int> status_;
};

/// True while the echo should keep running.
bool echo_should_run(pid_t parent, int64_t end_mono_ns) {
  return !g_stop.load() && getppid() == parent && monotonic_now_ns() < end_mono_ns;
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

/// An IPv4 UDP socket bound to 127.0.0.1:port (0 = any free port), with a receive timeout so
/// that blocking loops see their stop flags.
int loopback_udp_socket(uint16_t port) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(port);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    close(fd);
    throw std::runtime_error(std::string("bind 127.0.0.1: ") + std::strerror(err));
  }
  timeval tv{0, 100'000};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  return fd;
}

uint16_t local_port(int fd) {
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    throw std::runtime_error(std::string("getsockname: ") + std::strerror(errno));
  }
  return ntohs(addr.sin_port);
}

struct FdGuard {
  int fd;
  ~FdGuard() {
    if (fd >= 0) close(fd);
  }
};

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

// ---------------------------------------------------------------------------------------------
// the pinger

struct VariantResult {
  Variant variant{};
  uint64_t window_begin = 0;  // first measured sequence number
  uint64_t sent = 0;          // samples sent in the measured window
  uint64_t send_failed = 0;
  RttRecorder::Snapshot rtt;
  uint64_t overruns = 0;  // pacer, measured window only
  uint64_t skipped = 0;
  DurationHistogram lateness;  // release time - deadline, measured window only
  int64_t cpu_ping_ns = 0;     // CPU time of the pinger in the measured window
  int64_t cpu_echo_ns = -1;    // and of the echo (-1: unreadable)
};

std::vector<std::string> echo_args(Variant v, const Options& opt) {
  const double run_s = static_cast<double>(opt.warmup + opt.samples) / opt.rate_hz;
  // a hard upper bound on the echo's life even if the pinger vanished without a signal
  const double max_s = 2.0 * opt.timeout_s + 2.0 * run_s + 3.0 / opt.rate_hz + 30.0;
  std::vector<std::string> args{"--role",        "echo",
                                "--variant",     name_of(v),
                                "--domain",      std::to_string(opt.domain),
                                "--max-seconds", std::to_string(max_s)};
  if (!opt.pki.empty()) args.insert(args.end(), {"--pki", opt.pki});
  return args;
}

/// Paced sending: warm-up (at least opt.warmup samples and until a first reply came back), then
/// opt.samples measured samples, then a grace period for the last replies.
/// `send(seq)` sends sample `seq` (1, 2, ...) and returns false if it was refused.
void run_paced(const Options& opt, RttRecorder& rec, EchoProcess& echo, const std::function<bool(uint64_t)>& send,
               VariantResult& result) {
  teleop::MonotonicClock clock;
  const auto period_ns = static_cast<int64_t>(1e9 / opt.rate_hz);
  teleop::RatePacer pacer(clock, period_ns);
  const int64_t reply_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  uint64_t seq = 0;
  pacer.start();
  while (true) {
    if (g_stop.load()) throw Interrupted();
    const auto tick = pacer.wait_next();
    send(++seq);
    if (seq >= opt.warmup && rec.replies() > 0) break;
    if (tick.now_ns > reply_deadline) {
      echo.check_alive();
      throw std::runtime_error("the echo matched but no reply came back within " + seconds_text(opt.timeout_s) + " s");
    }
    if (seq % 256 == 0) echo.check_alive();
  }
  const uint64_t first = seq + 1;
  rec.open_window(first);
  result.window_begin = first;
  const uint64_t overruns0 = pacer.stats().overruns;
  const uint64_t skipped0 = pacer.stats().skipped;
  const int64_t ping_cpu0 = own_cpu_ns();
  const int64_t echo_cpu0 = echo.cpu_ns();
  for (uint64_t i = 0; i < opt.samples; ++i) {
    if (g_stop.load()) throw Interrupted();
    const auto tick = pacer.wait_next();
    result.lateness.record(tick.now_ns - tick.deadline_ns);
    if (!send(++seq)) ++result.send_failed;
    ++result.sent;
  }
  result.cpu_ping_ns = own_cpu_ns() - ping_cpu0;
  const int64_t echo_cpu1 = echo.cpu_ns();
  result.cpu_echo_ns = echo_cpu0 < 0 || echo_cpu1 < 0 ? -1 : echo_cpu1 - echo_cpu0;
  result.overruns = pacer.stats().overruns - overruns0;
  result.skipped = pacer.stats().skipped - skipped0;
  // grace: the last replies are still on their way
  const int64_t grace_end = monotonic_now_ns() + std::max<int64_t>(500 * kNsPerMs, 3 * period_ns);
  while (rec.received() < result.sent && monotonic_now_ns() < grace_end && !g_stop.load()) usleep(1'000);
  result.rtt = rec.snapshot();
  echo.check_alive();  // an echo that died mid-run explains the losses: say so
}

std::string session_source() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "bench-%08x", static_cast<unsigned>(getpid()));
  return buf;
}

VariantResult run_dds_variant(Variant v, const Options& opt) {
  VariantResult result;
  result.variant = v;
  const int64_t ready_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  EchoProcess echo(echo_args(v, opt));  // before any DDS entity of this variant exists
  echo.wait_ready(ready_deadline);

  RttRecorder rec(opt.samples);  // outlives the participant, whose callback feeds it
  const std::string source = session_source();
  transport::Participant participant(dds_config(v, opt.domain, "teleop_bench_ping", opt.pki, "leader"));
  transport::Publication<JointState> pub(participant, transport::topics::kLeaderState, source);
  pub.sample() = make_sample(source);
  auto reader =
      participant.make_reader<JointState>(transport::topics::kFollowerState, [&rec, &source](const JointState& reply) {
        const int64_t arrival = monotonic_now_ns();
        // only our own samples: another bench or demo on the same domain must not be counted
        if (reply.header().source() != source) {
          rec.on_stray();
          return;
        }
        rec.on_reply(reply.header().seq(), reply.header().stamp_mono_ns(), arrival);
      });

  while (pub.matched() < 1 || reader.matched() < 1) {
    if (g_stop.load()) throw Interrupted();
    echo.check_alive();
    if (monotonic_now_ns() > ready_deadline) {
      throw std::runtime_error(std::string("the ") + name_of(v) + " echo did not match within " +
                               seconds_text(opt.timeout_s) + " s (writer matched " + std::to_string(pub.matched()) +
                               ", reader matched " + std::to_string(reader.matched()) +
                               "); is DDS discovery blocked on domain " + std::to_string(opt.domain) + "?");
    }
    usleep(10'000);
  }

  run_paced(
      opt, rec, echo,
      [&pub](uint64_t /*seq*/) {
        return pub.publish();  // stamps the next seq (== the loop's count) and the monotonic time
      },
      result);
  return result;
}

VariantResult run_raw_udp_variant(const Options& opt, size_t payload_size, const std::vector<unsigned char>& fill) {
  VariantResult result;
  result.variant = Variant::kRawUdp;
  const int64_t ready_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  EchoProcess echo(echo_args(Variant::kRawUdp, opt));
  const std::string port_text = echo.wait_ready(ready_deadline);
  const int port = std::stoi(port_text);

  FdGuard sock{loopback_udp_socket(0)};
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(static_cast<uint16_t>(port));
  if (connect(sock.fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
    throw std::runtime_error(std::string("connect: ") + std::strerror(errno));
  }

  // payload: [0,8) monotonic stamp, [8,16) seq, [16,24) session token, then the CDR bytes of a
  // real sample, so that the datagram has exactly the serialized JointState's size
  const uint64_t token = static_cast<uint64_t>(getpid());
  std::vector<unsigned char> out(payload_size);
  std::copy(fill.begin(), fill.end(), out.begin());
  std::memcpy(out.data() + 16, &token, 8);

  RttRecorder rec(opt.samples);
  std::atomic<bool> receiving{true};
  std::thread receiver([&] {
    std::vector<unsigned char> in(65536);
    while (receiving.load(std::memory_order_relaxed)) {
      const ssize_t n = recv(sock.fd, in.data(), in.size(), 0);
      const int64_t arrival = monotonic_now_ns();
      if (n <= 0) continue;  // timeout slice or EINTR
      uint64_t got_token = 0;
      if (static_cast<size_t>(n) != payload_size || (std::memcpy(&got_token, in.data() + 16, 8), got_token != token)) {
        rec.on_stray();
        continue;
      }
      int64_t stamp = 0;
      uint64_t seq = 0;
      std::memcpy(&stamp, in.data(), 8);
      std::memcpy(&seq, in.data() + 8, 8);
      rec.on_reply(seq, stamp, arrival);
    }
  });
  struct JoinGuard {
    std::atomic<bool>& flag;
    std::thread& thread;
    ~JoinGuard() {
      flag.store(false);
      thread.join();
    }
  } join_guard{receiving, receiver};

  run_paced(
      opt, rec, echo,
      [&](uint64_t seq) {
        const int64_t stamp = monotonic_now_ns();
        std::memcpy(out.data(), &stamp, 8);
        std::memcpy(out.data() + 8, &seq, 8);
        return send(sock.fd, out.data(), out.size(), 0) == static_cast<ssize_t>(out.size());
      },
      result);
  return result;
}

// ---------------------------------------------------------------------------------------------
// report

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

// security on vs off, both over UDP in this run: latency percentiles and CPU per round trip
void print_security_ratio(const std::vector<VariantResult>& results) {
  const VariantResult* plain = find(results, Variant::kDdsUdp);
  const VariantResult* secure = find(results, Variant::kDdsSecure);
  if (plain == nullptr || secure == nullptr) return;
  const auto ratio = [&](double f) {
    return static_cast<double>(secure->rtt.histogram.percentile_ns(f)) /
           static_cast<double>(plain->rtt.histogram.percentile_ns(f));
  };
  std::printf("\nratio security on/off (dds-sec / dds-udp, same run):\n  p50 %5.2fx   p99 %5.2fx", ratio(0.50),
              ratio(0.99));
  if (cpu_us_per_round_trip(*plain) > 0 && cpu_us_per_round_trip(*secure) > 0) {
    std::printf("   cpu per round trip %5.2fx", cpu_us_per_round_trip(*secure) / cpu_us_per_round_trip(*plain));
  }
  std::printf("\n");
}

void print_results(const std::vector<VariantResult>& results) {
  std::printf("\n%-8s %8s %6s %9s %9s %9s %9s %9s %10s   %s\n", "variant", "samples", "lost", "p50_us", "p90_us",
              "p99_us", "max_us", "min_us", "cpu_us/rt", "pacer (measured window)");
  for (const auto& r : results) {
    const auto& h = r.rtt.histogram;
    std::printf("%-8s %8" PRIu64 " %6" PRIu64 " %9.1f %9.1f %9.1f %9.1f %9.1f %10.1f   overruns %" PRIu64
                ", skipped %" PRIu64 ", lateness p99 %.1f us\n",
                name_of(r.variant), r.sent, r.sent - r.rtt.received, us(h.percentile_ns(0.50)),
                us(h.percentile_ns(0.90)), us(h.percentile_ns(0.99)), us(h.max_ns()), us(h.min_ns()),
                cpu_us_per_round_trip(r), r.overruns, r.skipped, us(r.lateness.percentile_ns(0.99)));
    if (r.send_failed || r.rtt.duplicates || r.rtt.stray) {
      std::printf("         (send refused %" PRIu64 ", duplicate replies %" PRIu64 ", foreign replies ignored %" PRIu64
                  ")\n",
                  r.send_failed, r.rtt.duplicates, r.rtt.stray);
    }
  }
  const VariantResult* raw = nullptr;
  for (const auto& r : results) {
    if (r.variant == Variant::kRawUdp) raw = &r;
  }
  if (raw == nullptr || raw->rtt.received == 0) return;
  std::printf("\nratio teleop/raw (same run):\n");
  for (const auto& r : results) {
    if (r.variant == Variant::kRawUdp || r.rtt.received == 0) continue;
    const auto ratio = [&](double f) {
      return static_cast<double>(r.rtt.histogram.percentile_ns(f)) /
             static_cast<double>(raw->rtt.histogram.percentile_ns(f));
    };
    std::printf("  %-8s p50 %5.2fx   p99 %5.2fx\n", name_of(r.variant), ratio(0.50), ratio(0.99));
  }
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

int run_pinger(const Options& opt) {
  std::vector<Variant> variants;
  if (opt.transport == "udp" || opt.transport == "both") variants.push_back(Variant::kDdsUdp);
  if (opt.transport == "shm" || opt.transport == "both") variants.push_back(Variant::kDdsShm);
  if (!opt.pki.empty()) variants.push_back(Variant::kDdsSecure);
  variants.push_back(Variant::kRawUdp);

  const auto wire = serialize(make_sample(session_source()));
  transport::PubSubTypeOf<JointState>::type type;
  JointState probe = make_sample(session_source());
  const uint32_t size_bound = type.getSerializedSizeProvider(&probe)();
  std::printf("teleop_roundtrip_bench: %" PRIu64 " samples (+%" PRIu64 " warm-up) at %.0f Hz, DDS domain %d\n",
              opt.samples, opt.warmup, opt.rate_hz, opt.domain);
  std::printf(
      "payload: msg::JointState, %zu joints x 4 sequences = %zu bytes serialized (CDR incl. 4-byte "
      "encapsulation; the type's size provider bounds it at %u); raw UDP datagrams carry %zu bytes\n",
      kJoints, wire.size(), size_bound, wire.size());
  if (wire.size() < 24) throw std::runtime_error("serialized sample too small for the raw UDP header");

  std::vector<VariantResult> results;
  for (Variant v : variants) {
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Round-trip latency leader -> follower -> leader of a 7-joint JointState through the teleop transport "
      "(Fast DDS over UDP and shared memory), beside a raw UDP ping-pong of the same payload size",
      "teleop_roundtrip_bench"};
  Options opt;
  app.add_option("-n,--samples", opt.samples, "measured round trips per variant")
      ->check(CLI::Range(uint64_t{1}, uint64_t{10'000'000}))
      ->capture_default_str();
  app.add_option("--rate-hz", opt.rate_hz, "send rate (absolute deadlines)")
      ->check(CLI::Range(1.0, 100'000.0))
      ->capture_default_str();
  app.add_option("--domain", opt.domain, "DDS domain id (away from a running demo's)")
      ->check(CLI::Range(0, 232))
      ->capture_default_str();
  app.add_option("--transport", opt.transport,
                 "teleop variants to run: udp, shm or both; the raw UDP reference always runs")
      ->check(CLI::IsMember({"udp", "shm", "both"}))
      ->capture_default_str();
  app.add_option("--warmup", opt.warmup, "round trips sent and discarded before measuring (after matching)")
      ->capture_default_str();
  app.add_option("--csv", opt.csv, "write every measured round trip to this CSV file");
  app.add_option("--pki", opt.pki,
                 "also run dds-udp with DDS Security, identities from this folder (scripts/make_pki.sh DIR "
                 "--bench-identity)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--timeout", opt.timeout_s, "seconds the echo may take to start, match and first reply")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  // internal: how the benchmark starts its echo processes
  app.add_option("--role", opt.role)->check(CLI::IsMember({"ping", "echo"}))->group("");
  app.add_option("--variant", opt.variant)->group("");
  app.add_option("--ready-fd", opt.ready_fd)->group("");
  app.add_option("--max-seconds", opt.max_seconds)->group("");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  install_signal_handlers();
  // wake up at the deadline, not up to 50 us later (the kernel's default timer slack)
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  try {
    return opt.role == "echo" ? run_echo(opt) : run_pinger(opt);
  } catch (const Interrupted&) {
    std::fprintf(stderr, "teleop_roundtrip_bench: interrupted\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_roundtrip_bench%s: error: %s\n", opt.role == "echo" ? " (echo)" : "", e.what());
    return 1;
  }
}
