// teleop_arm_emulator: an arm of CiA 402 torque drives as a process on SocketCAN, for HIL: one
// emulated drive per joint (one raw socket each, filtered to its node's frames) turning the
// MuJoCo arm, both stepped by the real time elapsed (at 1 kHz where the host keeps it), so that
// the follower's `hardware: canopen`, candump or cansend can talk to them:
//   teleop_arm_emulator --drives YAML [--section follower] [--plant FOLLOWER_YAML] [--hand J:RAD]
//                       [--duration S]
// --drives: a configuration with `hardware: canopen` in --section (a follower's `follower`, a
// leader's master arm `leader.robot_arm`): its `canopen.drives` say which drive is on which
// interface with which node id and mechanics (docs/robots.md).
// --hand J:RAD: an operator's hand on the arm (a haptic master's, operator_hand.h): the first
// SIGUSR1 grips joint J (1-based) where it is and moves it by RAD at 0.2 rad/s, holding it there
// against what the drives render; the next lets go, the next grips again.
// --plant: a follower configuration with a `mujoco:` section (default: the shipped `follower`):
// the arm the drives turn, without its gravity compensation (the drives carry its weight).
// --duration 0 runs until SIGINT / SIGTERM. Prints one line per drive at exit.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "teleop/can/socketcan_bus.h"
#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/common/version.h"
#include "teleop/emulator/emulated_arm.h"
#include "teleop/emulator/operator_hand.h"
#include "teleop/robot/mujoco_backend.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
volatile std::sig_atomic_t g_grips = 0;  // SIGUSR1s received: an odd count grips
void on_signal(int) { g_stop = 1; }
void on_grip(int) { g_grips = g_grips + 1; }

// `path` ("leader.robot_arm") under root
teleop::ConfigNode section_at(const teleop::ConfigNode& root, const std::string& path) {
  teleop::ConfigNode node = root;
  for (size_t from = 0; from <= path.size();) {
    const size_t dot = std::min(path.find('.', from), path.size());
    node = node.child(path.substr(from, dot - from));
    from = dot + 1;
  }
  return node;
}

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

// "J:RAD" (J 1-based) as the hand on an arm of `joints` joints; throws naming the option
teleop::emulator::OperatorHandConfig parse_hand(const std::string& text, size_t joints) {
  const size_t colon = text.find(':');
  teleop::emulator::OperatorHandConfig hand;
  size_t j = 0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no ':'");
    j = std::stoul(text.substr(0, colon));
    hand.delta_rad = std::stod(text.substr(colon + 1));
  } catch (const std::exception&) {
    throw std::invalid_argument("--hand " + text + ": expected JOINT:RAD, e.g. 1:0.2");
  }
  if (j < 1 || j > joints || !std::isfinite(hand.delta_rad)) {
    throw std::invalid_argument("--hand " + text + ": joint 1.." + std::to_string(joints) + " and a finite angle");
  }
  hand.joint = j - 1;
  return hand;
}

// the hand's torque for the coming step; `toggled`: grip, or let go
void move_hand(teleop::emulator::OperatorHand& hand, bool toggled, int64_t dt_ns, teleop::emulator::EmulatedArm& arm,
               teleop::JointVector& hand_nm) {
  const size_t j = hand.config().joint;
  const teleop::robot::ArmState& state = arm.plant().state();
  if (toggled && hand.holding()) {
    hand.let_go();
  } else if (toggled) {
    hand.grip(state.q_rad[j]);
  }
  hand_nm[j] = hand.torque(state.q_rad[j], state.dq_radps[j], static_cast<double>(dt_ns) * 1e-9);
  arm.plant().set_external_torque(hand_nm);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"teleop_arm_emulator: an arm of CiA 402 torque drives turning the MuJoCo arm, on SocketCAN"};
  app.set_version_flag("--version", teleop::version_text());
  std::string drives_config;
  std::string section = "follower";
  std::string plant_config = "follower";
  std::string hand_option;
  double duration_s = 0.0;
  app.add_option("--drives", drives_config, "configuration with hardware: canopen (the drives)")->required();
  app.add_option("--section", section, "the drives' section of it: follower, or a leader's leader.robot_arm");
  app.add_option("--hand", hand_option, "JOINT:RAD: SIGUSR1 grips joint JOINT (1-based) and moves it by RAD; the next lets go");
  app.add_option("--plant", plant_config, "follower configuration with a mujoco: section (the arm), by path or name");
  app.add_option("--duration", duration_s, "run time [s], 0 = until SIGINT/SIGTERM")->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);

  std::vector<std::unique_ptr<teleop::can::SocketCanBus>> buses;
  std::unique_ptr<teleop::robot::MujocoHardware> arm;
  std::unique_ptr<teleop::emulator::EmulatedArm> emulated;
  std::optional<teleop::emulator::OperatorHand> hand;
  try {
    const teleop::ConfigNode drives_root =
        teleop::ConfigNode::load_file(teleop::resolve_config("nodes", drives_config));
    const auto drives = teleop::robot::parse_canopen_hardware(section_at(drives_root, section));
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
    if (!hand_option.empty()) hand.emplace(parse_hand(hand_option, arm->joints()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_arm_emulator: %s\n", e.what());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGUSR1, on_grip);
  std::sig_atomic_t grips_seen = 0;
  teleop::JointVector hand_nm{};
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
    const std::sig_atomic_t grips = g_grips;
    if (hand) move_hand(*hand, grips != grips_seen, elapsed_ns, *emulated, hand_nm);
    grips_seen = grips;
    emulated->step(static_cast<double>(elapsed_ns) * 1e-9);
  }
  print_drives(emulated->drives(), emulated->plant().state());
  const teleop::PacerStats& s = pacer.stats();
  std::printf("steps %llu, overruns %llu, skipped %llu\n", static_cast<unsigned long long>(s.cycles),
              static_cast<unsigned long long>(s.overruns), static_cast<unsigned long long>(s.skipped));
  return 0;
}
