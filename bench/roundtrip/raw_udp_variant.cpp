// The raw UDP reference (raw-udp): a ping-pong on 127.0.0.1 of datagrams the size of the
// serialized sample, beside which the teleop variants' cost is read.

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>

#include "loopback_udp.h"
#include "pinger.h"
#include "teleop/common/clock.h"

namespace teleop::bench {
namespace {

/// The receive thread's loop: a datagram of our size carrying our session token is a reply,
/// anything else a stray.
void receive_replies(int fd, size_t payload_size, uint64_t token, RttRecorder& rec,
                     const std::atomic<bool>& receiving) {
  std::vector<unsigned char> in(65536);
  while (receiving.load(std::memory_order_relaxed)) {
    const ssize_t n = recv(fd, in.data(), in.size(), 0);
    const int64_t arrival = monotonic_now_ns();
    if (n <= 0) continue;  // timeout slice or EINTR
    uint64_t got_token = 0;
    if (static_cast<size_t>(n) != payload_size || (std::memcpy(&got_token, in.data() + 16, 8), got_token != token)) {
      rec.on_stray();
      continue;
    }
    int64_t stamp = 0;
    uint64_t seq = 0;
    int32_t topic = 0;
    std::memcpy(&stamp, in.data(), 8);
    std::memcpy(&seq, in.data() + 8, 8);
    std::memcpy(&topic, in.data() + 24, 4);
    rec.on_reply(topic, seq, stamp, arrival);
  }
}

/// The receive thread, stopped and joined on every path.
class Receiver {
 public:
  Receiver(int fd, size_t payload_size, uint64_t token, RttRecorder& rec)
      : thread_([this, fd, payload_size, token, &rec] { receive_replies(fd, payload_size, token, rec, receiving_); }) {}
  ~Receiver() {
    receiving_.store(false);
    thread_.join();
  }
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;

 private:
  std::atomic<bool> receiving_{true};
  std::thread thread_;
};

}  // namespace

VariantResult run_raw_udp_variant(const Options& opt, size_t payload_size, const std::vector<unsigned char>& fill) {
  VariantResult result;
  result.variant = Variant::kRawUdp;
  const int64_t ready_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  EchoProcess echo(echo_args(Variant::kRawUdp, opt));
  const std::string port_text = echo.wait_ready(ready_deadline);
  const int port = std::stoi(port_text);

  FdGuard sock{loopback_udp_socket(0)};
  connect_loopback(sock.fd, static_cast<uint16_t>(port));

  // payload: [0,8) monotonic stamp, [8,16) seq, [16,24) session token, [24,28) topic index, then
  // the CDR bytes of a real sample, so that the datagram has exactly the serialized JointState's
  // size; one datagram per topic and cycle
  const uint64_t token = static_cast<uint64_t>(getpid());
  std::vector<unsigned char> out(payload_size);
  std::copy(fill.begin(), fill.end(), out.begin());
  std::memcpy(out.data() + 16, &token, 8);

  RttRecorder rec(opt.samples, opt.topics);
  Receiver receiver(sock.fd, payload_size, token, rec);

  run_paced(
      opt, rec, echo,
      [&](uint64_t seq) {
        bool ok = true;
        for (int32_t topic = 0; topic < opt.topics; ++topic) {
          const int64_t stamp = monotonic_now_ns();
          std::memcpy(out.data(), &stamp, 8);
          std::memcpy(out.data() + 8, &seq, 8);
          std::memcpy(out.data() + 24, &topic, 4);
          ok = send(sock.fd, out.data(), out.size(), 0) == static_cast<ssize_t>(out.size()) && ok;
        }
        return ok;
      },
      result);
  return result;
}

}  // namespace teleop::bench
