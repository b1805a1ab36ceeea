// HIL grasp over vcan: the teleop_hand node process (the adapter) drives the teleop_hand_emulator
// process whose nine drives turn the MuJoCo hand (--plant mujoco, config/models/svh_hand_grasp.xml):
// this test, as the operator, publishes HandCommand over DDS and closes the hand around the scene's
// object by feel (HandState's motor angles), has the emulator release the object's support (SIGUSR1),
// and checks in the emulator's simulation log (--sim-log) that the grasp holds the object for 5 s,
// that the 20 joint angles the node publishes are the simulation's, and that a fault (the CAN
// controller error passive, an error frame by cansend) puts the node into its safe hold with the
// object still in the hand. (Every fault class against the same grasp, in simulated time:
// test/hand/mujoco_hand_adapter_test.cpp.)
//
// The real-time limits of each wait are generous (safety caps, up to 400 s for the 4 s hold):
// the ASan build's emulator is slower again. Time is the simulation's (the log's t_s, a row every 20 ms of it; the grasp controller closes
// the fingers by it, so its steps stay small however slowly the emulator runs): in the TCG VM the MuJoCo hand runs at a
// third of real time or less (QEMU emulates the SSE floating point MuJoCo computes with in software), so the emulator
// is a time-dilated plant there, down to a twentieth of real time on a loaded host. The drives live in its time (a
// heartbeat every 100 ms of it); the node's timeouts are in real time and are set long enough for it (heartbeat 10 s,
// PDO 1 s), and the node does not home: its current-threshold homing assumes a plant in real time (a stalled emulator
// lets the homing target run ahead and the current pass the threshold before the stop). Homing into the model's limits
// is tested in process (test/hand/mujoco_hand_adapter_test.cpp). Run with the other vcan HIL tests in one VM boot
// (test/vcan/CMakeLists.txt).
#include <gtest/gtest.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "teleop/hand/grasp_closer.h"
#include "teleop/hand/hand_coupling.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"
#include "teleop/transport/topics.h"
#include "vcan_support.h"
#include "vm_bus.h"

namespace teleop::hand {
namespace {

using can::test::ChildProcess;
using can::test::EmulatorProcess;

// the model's motor ranges, 5 mrad inside: config/nodes/hand_mujoco.yaml's max_position_rad
constexpr HandMotorVector kMaxPositionRad{0.9654, 0.9829, 1.329, 0.7935, 1.271, 0.7935, 0.9767, 0.9767, 0.5716};

// One row of the emulator's --sim-log (hand/src/emulator/sim_log.h).
struct SimRow {
  double t_s = -1.0;
  std::array<double, 3> object_m{};
  bool supported = true;
  int contacts = 0;
  int links = 0;
  double force_n = 0.0;
  HandJointVector q_rad{};
};

// Follows the emulator's simulation log while it is written.
class SimLogReader {
 public:
  explicit SimLogReader(std::string path) : path_(std::move(path)) {}
  /// Reads the rows written since the last call; true when the latest row changed.
  bool poll() {
    if (!in_.is_open()) {
      in_.open(path_);
      if (!in_.is_open()) return false;
      std::getline(in_, partial_);  // the header (complete: flushed with the first row)
      partial_.clear();
    }
    bool changed = false;
    std::string chunk;
    while (std::getline(in_, chunk)) {
      if (in_.eof()) {  // no newline yet: the rest comes later
        partial_ += chunk;
        break;
      }
      parse(partial_ + chunk);
      partial_.clear();
      changed = true;
    }
    in_.clear();
    return changed;
  }
  const SimRow& latest() const { return latest_; }

 private:
  void parse(const std::string& line) {
    std::vector<double> v;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) v.push_back(cell.empty() ? 0.0 : std::stod(cell));
    if (v.size() < 8 + kHandJoints) return;
    SimRow r;
    r.t_s = v[0];
    r.object_m = {v[1], v[2], v[3]};
    r.supported = v[4] != 0.0;
    r.contacts = static_cast<int>(v[5]);
    r.links = static_cast<int>(v[6]);
    r.force_n = v[7];
    for (size_t j = 0; j < kHandJoints; ++j) r.q_rad[j] = v[8 + j];
    latest_ = r;
  }
  std::string path_;
  std::ifstream in_;
  std::string partial_;
  SimRow latest_;
};

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

transport::ParticipantConfig operator_participant(int domain) {
  transport::ParticipantConfig c = test::vm_participant(domain, "grasp_operator");
  // the node's QoS (config/nodes/hand_mujoco.yaml): a reader asking for a shorter deadline than
  // the node's writers offer would not match them
  c.liveliness_lease_ns = 250'000'000;
  c.participant_lease_ns = 3'000'000'000;
  c.stream_deadline_ns = 20'000'000;
  return c;
}

HandMotorVector positions(const msg::HandState& s) {
  HandMotorVector m{};
  for (size_t k = 0; k < kHandMotors; ++k) m[k] = s.position_rad()[k];
  return m;
}

// The operator: the node's topics, a command stream at 50 Hz, the simulation's clock, and the
// grasp controller it runs (closing, then holding: it keeps pressing the fingers that touch).
class Operator {
 public:
  Operator(int domain, const std::string& sim_log)
      : participant_(operator_participant(domain)),
        command_(participant_, transport::topics::kHandCommand, "grasp_operator"),
        state_(participant_, transport::topics::kHandState),
        joints_(participant_, transport::topics::kHandJoints),
        status_(participant_, transport::topics::kNodeStatus),
        sim_(sim_log) {}

  transport::Subscription<msg::HandState>& state() { return state_; }
  transport::Subscription<msg::JointState>& joints() { return joints_; }
  transport::Subscription<msg::NodeStatus>& status() { return status_; }
  const SimRow& sim() const { return sim_.latest(); }
  size_t command_matched() const { return command_.matched(); }
  /// Real time since the operator started [s].
  double wall_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

  void set_targets(const HandMotorVector& position_rad, const HandMotorVector& current_limit_a) {
    targets_ = position_rad;
    current_limit_a_ = current_limit_a;
    have_targets_ = true;
  }
  /// From now on the targets are the closer's, in the simulation's time since now.
  void grasp(GraspCloser& closer) {
    closer.start(positions(state_.latest()));
    closer_ = &closer;
    closer_start_s_ = sim().t_s;
    current_limit_a_ = closer.config().current_limit_a;
    have_targets_ = true;
  }
  /// Simulated time since the grasp began [s].
  double grasp_s() const { return sim().t_s - closer_start_s_; }
  /// One 20 ms round: publish the targets (once there are any), take what arrived.
  void round() {
    if (closer_ != nullptr) targets_ = closer_->update(grasp_s(), positions(state_.latest()));
    if (have_targets_) {
      auto& c = command_.sample();
      for (size_t k = 0; k < kHandMotors; ++k) {
        c.target_position_rad()[k] = targets_[k];
        c.current_limit_a()[k] = current_limit_a_[k];
      }
      c.enable(true);
      c.fault_reset(false);
      command_.publish();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    state_.poll();
    joints_.poll();
    status_.poll();
    sim_.poll();
    report_new_faults();
  }
  /// Rounds until `condition` holds (true) or `wall_s` passed (false).
  template <typename F>
  bool until(F condition, double wall_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(wall_s);
    while (!condition()) {
      if (std::chrono::steady_clock::now() > end) return false;
      round();
    }
    return true;
  }
  /// Rounds for `sim_s` of simulated time (at most `wall_s` of real time).
  bool for_sim(double sim_s, double wall_s) {
    const double end = sim().t_s + sim_s;
    return until([&] { return sim().t_s >= end; }, wall_s);
  }

 private:
  transport::Participant participant_;
  transport::Publication<msg::HandCommand> command_;
  transport::Subscription<msg::HandState> state_;
  transport::Subscription<msg::JointState> joints_;
  transport::Subscription<msg::NodeStatus> status_;
  // prints every fault bit the node reports as it appears, with both clocks (a fault the test did
  // not inject shows when and where the VM starved the processes)
  void report_new_faults() {
    if (!state_.has_sample()) return;
    for (size_t k = 0; k < kHandMotors; ++k) {
      const uint32_t now = state_.latest().faults()[k] & ~msg::HAND_FAULT_LIMIT;
      if ((now & ~seen_faults_[k]) != 0) {
        std::printf("fault bits 0x%x on motor %zu at %.2f s (simulated %.2f s)\n", now, k, wall_s(), sim().t_s);
      }
      seen_faults_[k] = now;
    }
  }
  std::array<uint32_t, kHandMotors> seen_faults_{};
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  SimLogReader sim_;
  GraspCloser* closer_ = nullptr;
  double closer_start_s_ = 0.0;
  HandMotorVector targets_{};
  HandMotorVector current_limit_a_{};
  bool have_targets_ = false;
};

TEST(HandGraspVcan, NodeClosesTheMujocoHandAroundTheObjectAndHoldsItThroughAFault) {
  const std::string sim_log = "/tmp/teleop_grasp_sim_" + std::to_string(::getpid()) + ".csv";
  const int domain = 60 + static_cast<int>(::getpid() % 100);
  EmulatorProcess emulator({"--plant", "mujoco", "--rate", "250", "--sim-log", sim_log});
  // the node as configured for the MuJoCo hand, with the time-dilated plant's longer timeouts and
  // without homing (see the top of the file); unicast discovery (the VM's loopback has no multicast)
  ChildProcess node({"teleop_hand",
                     "--config",
                     "hand_mujoco",
                     "--domain",
                     std::to_string(domain),
                     "--set",
                     "transport.initial_peers=[\"127.0.0.1\"]",
                     "--set",
                     "hand.interface=" + can::test::iface(),
                     "--set",
                     "hand.heartbeat_timeout_ms=10000",
                     "--set",
                     "hand.pdo_timeout_cycles=250",
                     "--set",
                     "hand.boot_timeout_ms=10000",
                     "--set",
                     "hand.sdo_timeout_ms=2000",
                     "--set",
                     "hand.enable_timeout_ms=5000",
                     "--set",
                     "hand.homing.enabled=false",
                     "--set",
                     "hand.command_timeout_ms=1000",
                     "--log-level",
                     "info"});
  Operator op(domain, sim_log);
  // boot, configuration, enabling: then the node publishes
  ASSERT_TRUE(op.until([&] { return op.state().has_sample() && op.sim().t_s > 0; }, 120.0))
      << "no HandState from teleop_hand (node running: " << node.running() << ", HandState " << op.state().has_sample()
      << ", NodeStatus " << op.status().has_sample() << ", command readers matched " << op.command_matched()
      << ", simulated time " << op.sim().t_s << " s)";
  // the hand open (while the drives were off, the fingers sank onto the object under gravity)
  op.set_targets(HandMotorVector{}, HandMotorVector{});
  ASSERT_TRUE(op.for_sim(0.5, 60.0));
  const SimRow supported = op.sim();
  ASSERT_TRUE(supported.supported);
  EXPECT_EQ(supported.contacts, 0);
  for (size_t k = 0; k < kHandMotors; ++k) EXPECT_NEAR(op.state().latest().position_rad()[k], 0.0, 0.01) << k;

  // close by feel: the targets advance until a finger stops following (the object holds it);
  // the grasp controller keeps running from here on
  GraspCloser closer(power_grasp(kMaxPositionRad));
  op.grasp(closer);
  ASSERT_TRUE(op.until([&] { return op.grasp_s() > 2.5; }, 300.0));
  int stopped = 0;
  for (size_t k = 0; k < kHandMotors; ++k) stopped += closer.in_contact(k) ? 1 : 0;
  std::printf("grasp over vcan: %d motors stopped by contact at sim t=%.2f s, %d links touch the object\n", stopped,
              op.sim().t_s, op.sim().links);
  EXPECT_GE(stopped, 4);  // 5 to 7: which fingers touch first varies with the timing

  // the support goes: for 5 s only the hand holds the object. Held: it stays in the hand (at
  // least 4 of the hand's links touch it all along, it never gets 40 mm from where the support
  // let it go: the grip may let it settle and slide a little until it wedges) and is at rest in
  // the end (less than 1 mm in the last second)
  ASSERT_TRUE(emulator.signal(SIGUSR1));
  ASSERT_TRUE(op.until([&] { return !op.sim().supported; }, 10.0));
  const SimRow released = op.sim();
  int fewest_links = released.links;
  double farthest_m = 0.0;
  const auto watch = [&] {
    fewest_links = std::min(fewest_links, op.sim().links);
    farthest_m = std::max(farthest_m, distance(op.sim().object_m, released.object_m));
  };
  ASSERT_TRUE(op.until(
      [&] {
        watch();
        return op.sim().t_s >= released.t_s + 4.0;
      },
      400.0));
  const SimRow second_to_last = op.sim();
  ASSERT_TRUE(op.until(
      [&] {
        watch();
        return op.sim().t_s >= released.t_s + 5.0;
      },
      150.0));
  const SimRow held = op.sim();
  std::printf(
      "held for %.2f s simulated: at least %d links touched the object, it got %.1f mm from where the support "
      "let it go and moved %.3f mm in the last second; %d links, %.1f N at the end\n",
      held.t_s - released.t_s, fewest_links, farthest_m * 1e3, distance(held.object_m, second_to_last.object_m) * 1e3,
      held.links, held.force_n);
  std::printf("motors: target / measured [rad] / current [A]:");
  for (size_t k = 0; k < kHandMotors; ++k) {
    std::printf(" %.3f/%.3f/%.2f", closer.targets()[k], op.state().latest().position_rad()[k],
                op.state().latest().current_a()[k]);
  }
  std::printf("\n");
  EXPECT_GE(fewest_links, 4);
  EXPECT_LT(farthest_m, 0.04);
  EXPECT_LT(distance(held.object_m, second_to_last.object_m), 1e-3);
  for (size_t k = 0; k < kHandMotors; ++k) {
    EXPECT_EQ(op.state().latest().faults()[k] & ~msg::HAND_FAULT_LIMIT, 0u) << k;
  }

  // the 20 joint angles the node publishes are the simulation's (at rest in the grasp): the main
  // joints to the encoder, the coupled ones within the mechanism's compliance under the grip
  ASSERT_TRUE(op.joints().has_sample());
  ASSERT_EQ(op.joints().latest().q_rad().size(), kHandJoints);
  const HandCoupling coupling = HandCoupling::svh();
  for (size_t j = 0; j < kHandJoints; ++j) {
    const bool main =
        coupling.terms()[j].factor == 1.0 && kHandJointNames[j] == kHandMotorNames[coupling.terms()[j].motor];
    EXPECT_NEAR(op.joints().latest().q_rad()[j], held.q_rad[j], main ? 2e-3 : 0.035) << kHandJointNames[j];
  }

  // a fault: the CAN controller goes error passive (an error frame, as its driver raises it); the
  // node goes to its safe hold (quick stop: every drive holds where it is) and keeps the object
  const auto passive = [&] {
    for (size_t k = 0; k < kHandMotors; ++k) {
      if ((op.state().latest().faults()[k] & msg::HAND_FAULT_BUS_PASSIVE) != 0) return true;
    }
    return false;
  };
  ASSERT_TRUE(can::test::cansend("20000004#0010000000000000"));
  ASSERT_TRUE(op.until(passive, 30.0));
  ASSERT_TRUE(
      op.until([&] { return op.status().has_sample() && op.status().latest().state() == msg::STATE_SAFE_HOLD; }, 10.0));
  const SimRow at_fault = op.sim();
  ASSERT_TRUE(op.for_sim(1.5, 150.0));
  std::printf("safe hold: object moved %.3f mm in %.2f s simulated, %d links\n",
              distance(op.sim().object_m, at_fault.object_m) * 1e3, op.sim().t_s - at_fault.t_s, op.sim().links);
  EXPECT_LT(distance(op.sim().object_m, at_fault.object_m), 5e-3);
  EXPECT_GE(op.sim().links, 4);
  EXPECT_EQ(op.status().latest().state(), msg::STATE_SAFE_HOLD);
  EXPECT_TRUE(node.running());
  std::printf("the emulator simulated %.1f s in %.1f s of real time (real-time factor %.2f in this VM)\n", op.sim().t_s,
              op.wall_s(), op.sim().t_s / op.wall_s());
  ::unlink(sim_log.c_str());
}

}  // namespace
}  // namespace teleop::hand
