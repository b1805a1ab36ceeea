// teleop_hand_emulator: the hand's motor controllers as a process on a SocketCAN interface.
// Runs N EmulatedDrives (one raw socket each, filtered to the frames addressed to its node),
// stepped in real time, so that a CANopen master, candump or cansend can talk to them:
//   teleop_hand_emulator --interface vcan0 [--nodes 1-9] [--rate 1000] [--duration 0]
// --duration 0 runs until SIGINT / SIGTERM. Prints one status line per node at exit.

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "teleop/can/emulated_drive.h"
#include "teleop/can/socketcan_bus.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

void usage() {
  std::fprintf(stderr,
               "usage: teleop_hand_emulator --interface IFACE [--nodes FIRST-LAST] [--rate HZ] "
               "[--duration S]\n");
}

int64_t now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1000000000LL + t.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  std::string interface;
  int first = 1;
  int last = 9;
  double rate_hz = 1000.0;
  double duration_s = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--interface" && has_value) {
      interface = argv[++i];
    } else if (a == "--nodes" && has_value) {
      const std::string v = argv[++i];
      const auto dash = v.find('-');
      first = std::atoi(v.substr(0, dash).c_str());
      last = dash == std::string::npos ? first : std::atoi(v.substr(dash + 1).c_str());
    } else if (a == "--rate" && has_value) {
      rate_hz = std::atof(argv[++i]);
    } else if (a == "--duration" && has_value) {
      duration_s = std::atof(argv[++i]);
    } else if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else {
      usage();
      return 2;
    }
  }
  if (interface.empty() || first < 1 || last > 127 || first > last || rate_hz <= 0.0 || rate_hz > 20000.0) {
    usage();
    return 2;
  }

  std::vector<std::unique_ptr<teleop::can::SocketCanBus>> buses;
  std::vector<std::unique_ptr<teleop::can::EmulatedDrive>> drives;
  try {
    for (int node = first; node <= last; ++node) {
      teleop::can::SocketCanOptions options;
      options.filters = teleop::can::canopen_node_filters(static_cast<uint8_t>(node));
      buses.push_back(std::make_unique<teleop::can::SocketCanBus>(interface, options));
      teleop::can::EmulatedDriveConfig config;
      config.node_id = static_cast<teleop::can::NodeId>(node);
      config.serial = static_cast<uint32_t>(node);
      drives.push_back(std::make_unique<teleop::can::EmulatedDrive>(*buses.back(), config));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_hand_emulator: %s\n", e.what());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::fprintf(stderr, "teleop_hand_emulator: nodes %d-%d on %s at %.0f Hz\n", first, last, interface.c_str(),
               rate_hz);

  const int64_t period_ns = static_cast<int64_t>(1e9 / rate_hz);
  const int64_t start = now_ns();
  const int64_t end = duration_s > 0.0 ? start + static_cast<int64_t>(duration_s * 1e9) : INT64_MAX;
  int64_t next = start;
  int64_t last_step = start;
  uint64_t overruns = 0;
  while (g_stop == 0 && next < end) {
    const int64_t t = now_ns();
    // step by the real time elapsed (bounded, so a long stall does not run minutes of physics)
    const double dt = static_cast<double>(std::min<int64_t>(t - last_step, 50 * period_ns)) * 1e-9;
    last_step = t;
    for (auto& d : drives) d->step(dt);
    next += period_ns;
    if (next < now_ns()) {
      ++overruns;
      next = now_ns();
    }
    const timespec wake{static_cast<time_t>(next / 1000000000LL), static_cast<long>(next % 1000000000LL)};
    ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
  }
  for (const auto& d : drives) {
    const auto& s = d->stats();
    std::fprintf(stderr, "node %u: nmt %s, rx %llu, tx %llu, sdo %llu, sync %llu\n", unsigned{d->node_id()},
                 teleop::can::to_string(d->nmt_state()), static_cast<unsigned long long>(s.frames_received),
                 static_cast<unsigned long long>(s.frames_sent), static_cast<unsigned long long>(s.sdo_requests),
                 static_cast<unsigned long long>(s.syncs));
  }
  std::fprintf(stderr, "teleop_hand_emulator: %llu cycle overruns\n", static_cast<unsigned long long>(overruns));
  return 0;
}
