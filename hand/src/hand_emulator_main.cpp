// teleop_hand_emulator: the hand's motor controllers as a process on a SocketCAN interface.
// Runs N EmulatedDrives (one raw socket each, filtered to the frames addressed to its node),
// stepped in real time, so that a CANopen master, candump or cansend can talk to them:
//   teleop_hand_emulator --interface vcan0 [--nodes 1-9] [--rate 1000] [--duration 0]
//                        [--inject SECONDS:NODE:KIND[:VALUE] ...]   (fault_schedule.h)
// --duration 0 runs until SIGINT / SIGTERM. Prints one status line per node at exit.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "teleop/can/socketcan_bus.h"
#include "teleop/common/version.h"
#include "teleop/hand/emulated_drive.h"
#include "teleop/hand/fault_schedule.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

int64_t now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1000000000LL + t.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_hand_emulator: the hand's CANopen motor controllers on a SocketCAN interface"};
  app.set_version_flag("--version", teleop::version_text());
  std::string interface;
  std::string nodes = "1-9";
  double rate_hz = 1000.0;
  double duration_s = 0.0;
  std::vector<std::string> inject;
  app.add_option("--interface", interface, "SocketCAN interface (vcan0, can0)")->required();
  app.add_option("--nodes", nodes, "node ids FIRST-LAST (or one id)");
  app.add_option("--rate", rate_hz, "drive step rate [Hz]")->check(CLI::Range(1.0, 20000.0));
  app.add_option("--duration", duration_s, "run time [s], 0 = until SIGINT/SIGTERM")->check(CLI::NonNegativeNumber);
  app.add_option("--inject", inject,
                 "fault at a time: SECONDS:NODE:KIND[:VALUE], KIND = heartbeat-stop|heartbeat-resume|emcy:CODE|"
                 "stall|free|drop-tpdo[:N]|tpdo-resume|drop-rpdo[:N]|rpdo-resume|refuse-sdo|accept-sdo|bus-off|"
                 "restarted (repeatable)");
  CLI11_PARSE(app, argc, argv);
  const auto dash = nodes.find('-');
  const int first = std::atoi(nodes.substr(0, dash).c_str());
  const int last = dash == std::string::npos ? first : std::atoi(nodes.substr(dash + 1).c_str());
  if (first < 1 || last > 127 || first > last) {
    std::fprintf(stderr, "teleop_hand_emulator: --nodes %s: need FIRST-LAST within 1-127\n", nodes.c_str());
    return 2;
  }
  std::vector<teleop::hand::ScheduledFault> faults;
  try {
    for (const std::string& spec : inject) {
      faults.push_back(teleop::hand::parse_fault_spec(spec));
      if (faults.back().node < first || faults.back().node > last) {
        throw std::invalid_argument("fault '" + spec + "': node is not emulated here");
      }
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "teleop_hand_emulator: %s\n", e.what());
    return 2;
  }
  std::sort(faults.begin(), faults.end(), [](const auto& a, const auto& b) { return a.at_s < b.at_s; });

  std::vector<std::unique_ptr<teleop::can::SocketCanBus>> buses;
  std::vector<std::unique_ptr<teleop::hand::EmulatedDrive>> drives;
  try {
    for (int node = first; node <= last; ++node) {
      teleop::can::SocketCanOptions options;
      options.filters = teleop::can::canopen_node_filters(static_cast<uint8_t>(node));
      // every RPDO2 COB-ID: a master may pack several nodes' targets into one frame on the id
      // of another node (dummy mapping, docs/can_bus_budget.md)
      options.filters.push_back({teleop::can::cob::kRpdo2, 0x780, false});
      buses.push_back(std::make_unique<teleop::can::SocketCanBus>(interface, options));
      teleop::hand::EmulatedDriveConfig config;
      config.node_id = static_cast<teleop::can::NodeId>(node);
      config.serial = static_cast<uint32_t>(node);
      drives.push_back(std::make_unique<teleop::hand::EmulatedDrive>(*buses.back(), config));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_hand_emulator: %s\n", e.what());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::fprintf(stderr, "teleop_hand_emulator: nodes %d-%d on %s at %.0f Hz, %zu faults scheduled\n", first, last,
               interface.c_str(), rate_hz, faults.size());
  size_t next_fault = 0;

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
    while (next_fault < faults.size() && t - start >= static_cast<int64_t>(faults[next_fault].at_s * 1e9)) {
      const teleop::hand::ScheduledFault& f = faults[next_fault++];
      const size_t i = f.node - static_cast<size_t>(first);
      const auto status = teleop::hand::apply_fault(f, *drives[i], *buses[i]);
      std::fprintf(stderr, "teleop_hand_emulator: t=%.3f s: injected %s into node %u: %s\n",
                   static_cast<double>(t - start) * 1e-9, teleop::hand::to_string(f.kind), unsigned{f.node},
                   teleop::can::to_string(status));
    }
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
