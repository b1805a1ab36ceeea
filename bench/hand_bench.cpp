// teleop_hand_bench: what the hand adapter costs and how long a command takes to reach the bus.
//   1. cycle cost: HandAdapter::cycle() timed on every cycle of an operational hand, with a new
//      target every cycle; on a VirtualCanBus with nine EmulatedDrives in this process
//      (--virtual, any host) or on SocketCAN against the teleop_hand_emulator process;
//   2. end to end (SocketCAN only): a HandCommand published on DDS by this process, through the
//      teleop_hand node process, to the first target RPDO on the bus carrying it, as the kernel
//      stamps its reception here (CLOCK_REALTIME both ends: one host).
// On a host without CAN run it inside the vcan VM (docs/hand_adapter.md):
//   test/vcan/run_in_vm.sh --bin build/default/bin/teleop_hand_bench --bin build/default/bin/teleop_hand
//     --bin build/default/bin/teleop_hand_emulator -- teleop_hand_bench --interface vcan0
// (one line)

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "teleop/can/socketcan_bus.h"
#include "teleop/can/virtual_can_bus.h"
#include "teleop/common/clock.h"
#include "teleop/common/histogram.h"
#include "teleop/drive/emulated_drive.h"
#include "teleop/hand/hand_adapter.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"
#include "teleop/transport/topics.h"

namespace {

using namespace teleop;
using hand::HandAdapter;
using hand::HandPhase;

struct Options {
  std::string interface = "vcan0";
  bool virtual_bus = false;
  bool dds = false;
  int cycles = 1250;
  int samples = 200;
  int domain = 77;
};

void sleep_until_ns(int64_t t) {
  const timespec ts{static_cast<time_t>(t / 1'000'000'000), static_cast<long>(t % 1'000'000'000)};
  ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

void print(const char* what, const DurationHistogram& h) {
  std::printf("%-44s n=%-6llu p50 %8.1f us  p90 %8.1f us  p99 %8.1f us  max %8.1f us\n", what,
              static_cast<unsigned long long>(h.count()), h.percentile_ns(0.5) * 1e-3, h.percentile_ns(0.9) * 1e-3,
              h.percentile_ns(0.99) * 1e-3, h.max_ns() * 1e-3);
}

// a child process, SIGTERM'ed when it goes away; its output into `log` when one is given
class Child {
 public:
  explicit Child(std::vector<std::string> args, const std::string& log = {}) {
    pid_ = ::fork();
    if (pid_ == 0) {
      if (!log.empty()) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, 1);
        ::dup2(fd, 2);
      }
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execvp(argv[0], argv.data());
      std::_Exit(127);
    }
  }
  ~Child() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

 private:
  pid_t pid_ = -1;
};

// the cycle-cost loop: an operational hand, a new target every cycle, cycle() timed
DurationHistogram time_cycles(HandAdapter& adapter, int cycles, const std::function<void()>& between) {
  const int64_t period = static_cast<int64_t>(1e9 / adapter.config().cycle_rate_hz);
  int64_t next = monotonic_now_ns();
  while (adapter.phase() != HandPhase::kOperational && adapter.phase() != HandPhase::kFailed &&
         adapter.phase() != HandPhase::kSafeHold) {
    adapter.cycle(next);
    between();
    next += period;
    sleep_until_ns(next);
  }
  if (adapter.phase() != HandPhase::kOperational) throw std::runtime_error(adapter.message());
  DurationHistogram h;
  for (int i = 0; i < cycles; ++i) {
    hand::HandTargets t;
    t.position_rad.fill(0.5 + 0.3 * std::sin(i * 0.01));
    t.enable = true;
    const int64_t start = monotonic_now_ns();
    adapter.set_command(t);
    adapter.cycle(next);
    h.record(monotonic_now_ns() - start);
    between();
    next += period;
    if (monotonic_now_ns() - next > 50 * period) next = monotonic_now_ns();
    sleep_until_ns(next);
  }
  return h;
}

void cycle_cost_virtual(const Options& o) {
  can::VirtualCanBus bus;
  auto adapter_ep = bus.open("adapter");
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> eps;
  std::vector<std::unique_ptr<drive::EmulatedDrive>> drives;
  for (can::NodeId n = 1; n <= 9; ++n) {
    eps.push_back(bus.open("drive"));
    drive::EmulatedDriveConfig c;
    c.node_id = n;
    drives.push_back(std::make_unique<drive::EmulatedDrive>(*eps.back(), c));
  }
  HandAdapter adapter(*adapter_ep, hand::HandAdapterConfig{});
  // the drives run between the cycles, outside the timed call
  const auto h = time_cycles(adapter, o.cycles, [&] {
    for (auto& d : drives) d->step(4e-3);
  });
  print("adapter cycle, VirtualCanBus + 9 EmulatedDrives", h);
}

hand::HandAdapterConfig vm_config() {
  hand::HandAdapterConfig c;  // the HIL tests' timeouts: a TCG VM stalls
  c.pdo_timeout_cycles = 75;
  c.heartbeat_timeout_s = 1.0;
  c.boot_timeout_s = 5.0;
  c.sdo_timeout_s = 1.0;
  c.enable_timeout_s = 3.0;
  return c;
}

// The adapter's share of the command latency: set_command() at a random phase of the 4 ms
// cycle, to the kernel's receive stamp of the first target RPDO carrying it (an observer socket
// in this process; CLOCK_REALTIME both ends).
void command_to_bus(HandAdapter& adapter, const Options& o) {
  can::SocketCanOptions so;
  so.filters = {{0x301, 0x7FF, false}};  // the target RPDO of motors 0 and 1
  can::SocketCanBus observer(o.interface, so);
  const int64_t period = static_cast<int64_t>(1e9 / adapter.config().cycle_rate_hz);
  DurationHistogram h;
  int lost = 0;
  int64_t next = monotonic_now_ns();
  for (int k = 0; k < o.samples; ++k) {
    // a few cycles, then the command at a phase that walks through the cycle
    for (int i = 0; i < 3; ++i) {
      sleep_until_ns(next);
      adapter.cycle(next);
      next += period;
    }
    // between the cycle just run and the next one
    sleep_until_ns(next - period + (period * (k % 10)) / 10);
    const double target = 0.3 + 0.002 * (k % 200);
    const int32_t ticks = *adapter.channel(0).rad_to_ticks(target);
    hand::HandTargets t;
    t.position_rad.fill(target);
    t.enable = true;
    const int64_t commanded_ns = system_now_ns();
    adapter.set_command(t);
    bool seen = false;
    for (int i = 0; i < 20 && !seen; ++i) {
      sleep_until_ns(next);
      adapter.cycle(next);
      next += period;
      can::CanFrame f;
      int64_t rx_ns = 0;
      while (!seen && observer.receive(f, std::chrono::milliseconds(2), rx_ns) == can::CanStatus::kOk) {
        if (!f.error() && static_cast<int32_t>(can::le::get_u32(f.data.data())) == ticks) {
          h.record(rx_ns - commanded_ns);
          seen = true;
        }
      }
    }
    if (!seen) ++lost;
    if (monotonic_now_ns() - next > 50 * period) next = monotonic_now_ns();
  }
  print("set_command -> target RPDO on the bus", h);
  std::printf("  (%d of %d commands never seen on the bus)\n", lost, o.samples);
}

void cycle_cost_socketcan(const Options& o) {
  const hand::HandAdapterConfig config = vm_config();
  can::SocketCanOptions so;
  so.filters = can::canopen_master_filters(config.node_ids);
  can::SocketCanBus bus(o.interface, so);
  HandAdapter adapter(bus, config);
  const auto h = time_cycles(adapter, o.cycles, [] {});
  print("adapter cycle, SocketCAN + emulator process", h);
  std::printf("  (%llu SYNC, %llu TPDOs received, %llu send failures)\n",
              static_cast<unsigned long long>(adapter.stats().syncs_sent),
              static_cast<unsigned long long>(adapter.stats().tpdos_received),
              static_cast<unsigned long long>(adapter.stats().send_failures));
  command_to_bus(adapter, o);
}

std::string write_node_config(const Options& o) {
  const std::string path = "/tmp/teleop_hand_bench.yaml";
  std::ofstream f(path);
  f << "node: {name: hand, rate_hz: 250, status_rate_hz: 10, duration_s: 0, realtime: off}\n"
    << "transport: {domain_id: " << o.domain
    << ", udpv4: true, shm: false, initial_peers: ['127.0.0.1'], interface_whitelist: ['127.0.0.1'], "
       "liveliness_lease_ms: 2000, "
       "participant_lease_ms: 10000, stream_deadline_ms: 100}\n"
    << "hand:\n  interface: " << o.interface << "\n"
    << "  heartbeat_timeout_ms: 1000\n  boot_timeout_ms: 5000\n  sdo_timeout_ms: 1000\n  enable_timeout_ms: 3000\n"
    << "  pdo_timeout_cycles: 75\n  command_timeout_ms: 1000\n";
  return path;
}

void end_to_end(const Options& o) {
  const std::string node_log = "/tmp/teleop_hand_bench_node.log";
  Child node({"teleop_hand", "--config", write_node_config(o)}, node_log);
  transport::ParticipantConfig pc;
  pc.name = "hand_bench";
  pc.domain_id = o.domain;
  pc.udpv4 = true;
  pc.shm = false;
  pc.initial_peers = {"127.0.0.1"};
  pc.interface_whitelist = {"127.0.0.1"};  // the VM has only lo
  transport::Participant participant(pc);
  transport::Publication<msg::HandCommand> command(participant, transport::topics::kHandCommand, "bench");
  transport::Subscription<msg::HandState> state(participant, transport::topics::kHandState);
  can::SocketCanOptions so;
  so.filters = {{0x301, 0x7FF, false}};  // the target RPDO of motors 0 and 1
  can::SocketCanBus bus(o.interface, so);
  // wait for the node: its HandState arrives once it is operational
  const int64_t deadline = monotonic_now_ns() + 60'000'000'000LL;
  while (state.poll() == 0 && monotonic_now_ns() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (!state.has_sample()) {
    std::ifstream log(node_log);
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    throw std::runtime_error("no HandState from teleop_hand within 60 s; its output:\n" + text);
  }
  const hand::MotorChannel channel(hand::HandAdapterConfig{}.channels[0]);
  DurationHistogram h;
  int lost = 0;
  for (int k = 0; k < o.samples; ++k) {
    const double target = 0.3 + 0.002 * (k % 200);
    auto& c = command.sample();
    c.target_position_rad().fill(target);
    c.enable(true);
    const int32_t ticks = *channel.rad_to_ticks(target);
    command.publish();
    const int64_t sent_ns = command.sample().header().stamp_ns();
    bool seen = false;
    const int64_t give_up = monotonic_now_ns() + 1'000'000'000;
    while (!seen && monotonic_now_ns() < give_up) {
      can::CanFrame f;
      int64_t rx_ns = 0;
      if (bus.receive(f, std::chrono::milliseconds(50), rx_ns) != can::CanStatus::kOk || f.error()) continue;
      if (static_cast<int32_t>(can::le::get_u32(f.data.data())) == ticks) {
        h.record(rx_ns - sent_ns);
        seen = true;
      }
    }
    if (!seen) ++lost;
    state.poll();
    // a random phase against the node's 4 ms cycle
    std::this_thread::sleep_for(std::chrono::microseconds(20'000 + 997 * (k % 7)));
  }
  print("HandCommand on DDS -> target RPDO on the bus", h);
  std::printf("  (%d of %d commands never seen on the bus)\n", lost, o.samples);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_hand_bench: hand adapter cycle cost and command-to-bus latency"};
  Options o;
  app.add_option("--interface", o.interface, "SocketCAN interface with the emulator (default vcan0)");
  app.add_flag("--virtual", o.virtual_bus, "cycle cost on a VirtualCanBus only (no CAN, no DDS)");
  app.add_flag("--dds", o.dds, "also HandCommand on DDS -> bus through a teleop_hand process (see docs)");
  app.add_option("--cycles", o.cycles, "timed adapter cycles")->check(CLI::Range(10, 1'000'000));
  app.add_option("--samples", o.samples, "end-to-end samples")->check(CLI::Range(1, 100'000));
  app.add_option("--domain", o.domain, "DDS domain")->check(CLI::Range(0, 232));
  CLI11_PARSE(app, argc, argv);
  try {
    if (o.virtual_bus) {
      cycle_cost_virtual(o);
      return 0;
    }
    {
      Child emulator({"teleop_hand_emulator", "--interface", o.interface});
      cycle_cost_socketcan(o);
      if (o.dds) end_to_end(o);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_hand_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
