// teleop_arm_emulator: an arm of CiA 402 torque drives as a process on SocketCAN, for HIL: one
// emulated drive per joint (one raw socket each, filtered to its node's frames) turning the
// MuJoCo arm, both stepped by the real time elapsed (at 1 kHz where the host keeps it), so that
// the follower's `hardware: canopen`, candump or cansend can talk to them:
//   teleop_arm_emulator --drives FOLLOWER_YAML [--plant FOLLOWER_YAML] [--duration S]
// --drives: a follower configuration with `hardware: canopen`: its `canopen.drives` say which
// drive is on which interface with which node id and mechanics (docs/robots.md).
// --plant: a follower configuration with a `mujoco:` section (default: the shipped `follower`):
// the arm the drives turn, without its gravity compensation (the drives carry its weight).
// --duration 0 runs until SIGINT / SIGTERM. Prints one line per drive at exit.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <climits>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "teleop/can/socketcan_bus.h"
#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/common/version.h"
#include "teleop/emulator/emulated_arm.h"
#include "teleop/robot/mujoco_backend.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

constexpr double kStepS = 1e-3;
constexpr int64_t kMaxStepNs = 5'000'000;

void print_drives(const teleop::drive::DriveGroup& drives, const teleop::robot::ArmState& arm) {
  for (size_t k = 0; k < drives.drives(); ++k) {
    const teleop::drive::EmulatedDrive& d = drives.drive(k);
    const teleop::drive::EmulatedDriveStats& s = d.stats();
    std::printf("drive %u joint %zu: %s, nmt %s, q %.4f rad, torque %d permille, frames in %llu out %llu, syncs %llu, "
                "emcys %llu, master lost %llu\n",
                unsigned{d.node_id()}, k + 1, teleop::can::cia402::to_string(d.state()),
                teleop::can::to_string(d.nmt_state()), arm.q_rad[k], int{d.target_torque_permille()},
                static_cast<unsigned long long>(s.frames_received), static_cast<unsigned long long>(s.frames_sent),
                static_cast<unsigned long long>(s.syncs), static_cast<unsigned long long>(s.emcys_sent),
                static_cast<unsigned long long>(s.heartbeat_timeouts));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_arm_emulator: an arm of CiA 402 torque drives turning the MuJoCo arm, on SocketCAN"};
  app.set_version_flag("--version", teleop::version_text());
  std::string drives_config;
  std::string plant_config = "follower";
  double duration_s = 0.0;
  app.add_option("--drives", drives_config, "follower configuration with hardware: canopen (the drives)")->required();
  app.add_option("--plant", plant_config, "follower configuration with a mujoco: section (the arm), by path or name");
  app.add_option("--duration", duration_s, "run time [s], 0 = until SIGINT/SIGTERM")->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);

  std::vector<std::unique_ptr<teleop::can::SocketCanBus>> buses;
  std::unique_ptr<teleop::robot::MujocoHardware> arm;
  std::unique_ptr<teleop::emulator::EmulatedArm> emulated;
  try {
    const teleop::ConfigNode drives_root =
        teleop::ConfigNode::load_file(teleop::resolve_config("nodes", drives_config));
    const auto drives = teleop::robot::parse_canopen_hardware(drives_root.child("follower"));
    const teleop::ConfigNode plant_root = teleop::ConfigNode::load_file(teleop::resolve_config("nodes", plant_config));
    teleop::robot::MujocoHardwareConfig plant = teleop::robot::parse_mujoco_hardware(plant_root.child("follower"))->config();
    plant.gravity_compensated = false;
    plant.period_s = kStepS;
    arm = std::make_unique<teleop::robot::MujocoHardware>(plant);
    std::vector<teleop::can::CanBus*> endpoints;
    for (const teleop::robot::CanopenJointConfig& joint : drives->config().joints) {
      teleop::can::SocketCanOptions options;
      options.filters = teleop::can::canopen_node_filters(joint.node);
      // and the master's heartbeat, which the drive consumes (0x1016): without it the drive never
      // starts watching its master and keeps applying the last torque after the master died
      options.filters.push_back({0x700u + drives->config().master_node, 0x7FF});
      buses.push_back(std::make_unique<teleop::can::SocketCanBus>(joint.bus, options));
      endpoints.push_back(buses.back().get());
    }
    emulated = std::make_unique<teleop::emulator::EmulatedArm>(*arm, kStepS, drives->config(), endpoints);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_arm_emulator: %s\n", e.what());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  teleop::MonotonicClock clock;
  teleop::RatePacer pacer(clock, static_cast<int64_t>(kStepS * 1e9));
  pacer.start();
  const int64_t start_ns = clock.now_ns();
  const int64_t end_ns = duration_s > 0.0 ? start_ns + static_cast<int64_t>(duration_s * 1e9) : INT64_MAX;
  int64_t stepped_ns = start_ns;
  while (!g_stop && stepped_ns < end_ns) {
    const teleop::CycleTick tick = pacer.wait_next();
    // by the real time elapsed, so that the drives' clocks (their heartbeats, their watch of the
    // master's) keep the master's pace where a wake comes late; in pieces of at most 5 ms, so that
    // where the arm cannot be simulated in real time (QEMU without KVM: a MuJoCo step takes 2 ms)
    // the drives still answer every few milliseconds, and the arm and its drives run slower than
    // real time together (a time-dilated plant) rather than in bursts of 50 ms
    const int64_t elapsed_ns = std::min<int64_t>(tick.now_ns - stepped_ns, kMaxStepNs);
    stepped_ns = tick.now_ns;
    emulated->step(static_cast<double>(elapsed_ns) * 1e-9);
  }
  print_drives(emulated->drives(), emulated->plant().state());
  const teleop::PacerStats& s = pacer.stats();
  std::printf("steps %llu, overruns %llu, skipped %llu\n", static_cast<unsigned long long>(s.cycles),
              static_cast<unsigned long long>(s.overruns), static_cast<unsigned long long>(s.skipped));
  return 0;
}
