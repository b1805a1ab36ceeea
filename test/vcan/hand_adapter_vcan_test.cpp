// HIL tests of the hand adapter on a virtual CAN interface against the real teleop_hand_emulator
// process: boot, configuration, homing, tracking (RMSE reported), each fault into the safe state
// and out by fault reset, with cansend / candump as independent peers. Run by the vcan harness
// (test/vcan/run_in_vm.sh): in a qemu VM where the host kernel has no CAN.
#include <gtest/gtest.h>
#include <time.h>

#include <algorithm>
#include <cstdint>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "teleop/can/socketcan_bus.h"
#include "teleop/drive/emulated_drive.h"
#include "teleop/hand/hand_adapter.h"
#include "teleop/drive/drive_objects.h"
#include "vcan_support.h"

namespace teleop::hand {
namespace {

using namespace can;  // the CANopen core the hand is built on
using can::test::cansend;
using can::test::iface;

int64_t monotonic_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1'000'000'000LL + t.tv_nsec;
}

// The TCG VM on a shared, loaded host stalls for up to some hundred milliseconds: the timeouts
// leave room for that (the defaults of config/nodes/hand.yaml are for a real machine).
HandAdapterConfig vm_config() {
  HandAdapterConfig c;
  c.pdo_timeout_cycles = 75;  // 300 ms
  c.heartbeat_timeout_s = 1.0;
  c.boot_timeout_s = 5.0;
  c.sdo_timeout_s = 1.0;
  c.enable_timeout_s = 3.0;
  return c;
}

SocketCanOptions master_options(const HandAdapterConfig& c) {
  SocketCanOptions o;
  o.filters = canopen_master_filters(c.node_ids);
  return o;
}

// "60N#23002FSSVVVVVVVV": an expedited 4-byte SDO download to the fault injection object
std::string injection_frame(NodeId node, uint8_t subindex, uint32_t value) {
  char text[64];
  std::snprintf(text, sizeof text, "%03X#23%02X%02X%02X%02X%02X%02X%02X", 0x600u + node, drive::drive_od::kFaultInjection & 0xFF,
                drive::drive_od::kFaultInjection >> 8, subindex, value & 0xFF, (value >> 8) & 0xFF, (value >> 16) & 0xFF,
                value >> 24);
  return text;
}

// The adapter in this process on a SocketCanBus, paced at its rate on absolute deadlines.
class HandOnVcan {
 public:
  explicit HandOnVcan(const HandAdapterConfig& config = vm_config(), const std::vector<std::string>& emulator_args = {})
      : emulator_(emulator_args), bus_(iface(), master_options(config)), adapter_(bus_, config) {
    period_ns_ = static_cast<int64_t>(1e9 / config.cycle_rate_hz);
    next_ns_ = monotonic_ns();
  }

  HandAdapter& adapter() { return adapter_; }
  SocketCanBus& bus() { return bus_; }

  void cycle() {
    adapter_.cycle(next_ns_);
    next_ns_ += period_ns_;
    // late wake-ups (the TCG VM's timers often are) are caught up on the absolute schedule;
    // only after a long stall does the schedule restart from now
    if (monotonic_ns() - next_ns_ > 50 * period_ns_) {
      skipped_ += static_cast<uint64_t>((monotonic_ns() - next_ns_) / period_ns_);
      next_ns_ = monotonic_ns();
    }
    const timespec t{static_cast<time_t>(next_ns_ / 1'000'000'000), static_cast<long>(next_ns_ % 1'000'000'000)};
    ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr);
  }
  void run(double seconds, const std::function<void(double)>& each = {}) {
    const int64_t end = monotonic_ns() + static_cast<int64_t>(seconds * 1e9);
    const int64_t start = monotonic_ns();
    while (monotonic_ns() < end) {
      if (each) each(static_cast<double>(monotonic_ns() - start) * 1e-9);
      cycle();
    }
  }
  bool run_until(HandPhase phase, double seconds) {
    const int64_t end = monotonic_ns() + static_cast<int64_t>(seconds * 1e9);
    while (adapter_.phase() != phase && monotonic_ns() < end) cycle();
    return adapter_.phase() == phase;
  }
  void command(double rad, bool fault_reset = false, double current_limit_a = 0.0) {
    HandTargets t;
    t.position_rad.fill(rad);
    t.current_limit_a.fill(current_limit_a);
    t.enable = true;
    t.fault_reset = fault_reset;
    adapter_.set_command(t);
  }
  /// Writes the emulator's fault injection object with cansend and waits until the drive has
  /// taken it: its SDO answer reaches our bus as a response nobody here asked for. (The emulator
  /// lags behind the bus by up to some hundred milliseconds in the VM.)
  bool inject(NodeId node, uint8_t subindex, uint32_t value) {
    const uint64_t before = adapter_.stats().unexpected_frames;
    if (!cansend(injection_frame(node, subindex, value))) return false;
    const int64_t end = monotonic_ns() + 5'000'000'000LL;
    while (adapter_.stats().unexpected_frames == before && monotonic_ns() < end) cycle();
    return adapter_.stats().unexpected_frames > before;
  }
  /// Cycles until `condition` holds (true) or `seconds` passed (false).
  bool run_until(const std::function<bool(const HandAdapter&)>& condition, double seconds) {
    const int64_t end = monotonic_ns() + static_cast<int64_t>(seconds * 1e9);
    while (!condition(adapter_) && monotonic_ns() < end) cycle();
    return condition(adapter_);
  }
  /// Until the motor reports this fault bit. (On a loaded host the starved VM may add faults of
  /// its own, such as a late heartbeat: the test looks for the one it caused.)
  bool run_until_fault(size_t motor, uint32_t bit, double seconds) {
    return run_until([&](const HandAdapter& a) { return (a.feedback().faults[motor] & bit) != 0; }, seconds);
  }
  /// Rising edges of fault_reset, as an operator would press reset, every 0.5 s until operational.
  bool reset_and_recover(double rad, double seconds = 5.0) {
    const int64_t end = monotonic_ns() + static_cast<int64_t>(seconds * 1e9);
    do {
      command(rad, false);
      cycle();
      command(rad, true);
      if (run_until(HandPhase::kOperational, std::min(0.5, seconds))) return true;
    } while (monotonic_ns() < end);
    return false;
  }

 private:
  test::EmulatorProcess emulator_;
  SocketCanBus bus_;
  HandAdapter adapter_;
  int64_t period_ns_ = 4'000'000;
  int64_t next_ns_ = 0;
  uint64_t skipped_ = 0;

 public:
  /// Deadlines dropped after long stalls (the schedule restarted from the time it woke up).
  uint64_t skipped() const { return skipped_; }
};

void expect_operational(HandOnVcan& hand) {
  ASSERT_TRUE(hand.run_until(HandPhase::kOperational, 15.0))
      << to_string(hand.adapter().phase()) << ": " << hand.adapter().message() << " (cycles "
      << hand.adapter().stats().cycles << ", SDO writes " << hand.adapter().stats().sdo_writes << ", TPDOs "
      << hand.adapter().stats().tpdos_received << ", bus " << to_string(hand.bus().state()) << ")";
}

TEST(HandAdapterVcan, BootsConfiguresHomesAndTracksAFingerTrajectory) {
  HandAdapterConfig config = vm_config();
  config.homing.enabled = true;
  HandOnVcan hand(config);
  ASSERT_TRUE(hand.run_until(HandPhase::kHoming, 15.0)) << hand.adapter().message();
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  // after homing the hard stop reads -0.1 rad and the hand holds at the lower limit, 0
  hand.run(0.5);
  for (size_t m = 0; m < kHandMotors; ++m) EXPECT_NEAR(hand.adapter().feedback().position_rad[m], 0.0, 0.01) << m;

  // a grasp-like motion: every finger 0.2 -> 0.8 rad and back at 0.5 Hz, phase-shifted per finger
  std::vector<HandMotorVector> sent;
  std::vector<HandMotorVector> measured;
  hand.command(0.2);
  hand.run(0.5);
  hand.run(4.0, [&](double t) {
    HandTargets targets;
    for (size_t m = 0; m < kHandMotors; ++m) {
      targets.position_rad[m] = 0.5 - 0.3 * std::cos(2 * M_PI * 0.5 * t + 0.2 * static_cast<double>(m));
    }
    targets.enable = true;
    hand.adapter().set_command(targets);
    sent.push_back(hand.adapter().feedback().target_rad);
    measured.push_back(hand.adapter().feedback().position_rad);
  });
  ASSERT_EQ(hand.adapter().phase(), HandPhase::kOperational) << hand.adapter().message();
  // RMSE of the feedback against the target sent `lag` cycles earlier: a target goes out after
  // SYNC k, is applied at SYNC k+1 and sampled in the TPDO of SYNC k+2
  auto rmse = [&](size_t lag) {
    double sum = 0;
    size_t n = 0;
    for (size_t k = lag + 25; k < sent.size(); ++k) {
      for (size_t m = 0; m < kHandMotors; ++m) {
        const double e = measured[k][m] - sent[k - lag][m];
        sum += e * e;
        ++n;
      }
    }
    return std::sqrt(sum / static_cast<double>(n));
  };
  const double rmse_now = rmse(0);
  const double rmse_lag2 = rmse(2);
  std::printf("HIL tracking over vcan: %zu cycles, RMSE %.4f rad (same cycle), %.4f rad (2-cycle bus latency removed)\n",
              sent.size(), rmse_now, rmse_lag2);
  RecordProperty("tracking_rmse_rad", std::to_string(rmse_now));
  RecordProperty("tracking_rmse_lag2_rad", std::to_string(rmse_lag2));
  EXPECT_GT(sent.size(), 500u);       // the loop ran (4 s at 250 Hz, VM stalls allowed)
  // a sanity bound, not a performance claim: the fingers follow the 0.6 rad swing (an idle
  // machine gives ~0.004 rad, a starved VM on a loaded host up to ~0.035; docs/hand_adapter.md)
  EXPECT_LT(rmse_lag2, 0.1);
  EXPECT_EQ(hand.adapter().stats().sdo_aborts, 0u);
}

// One fault: safe hold with the fault bit and the node in the message; the reset fails while
// the cause persists and succeeds after it is cleared.
struct FaultCase {
  const char* name;
  size_t motor;
  uint32_t bit;
  std::function<void(HandOnVcan&)> inject;
  std::function<void(HandOnVcan&)> clear;
};

void fault_and_recovery(const FaultCase& c) {
  HandOnVcan hand;
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  hand.command(0.4);
  hand.run(0.5);
  c.inject(hand);
  ASSERT_TRUE(hand.run_until_fault(c.motor, c.bit, 5.0)) << c.name << ": " << hand.adapter().message();
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kSafeHold) << c.name;
  std::printf("%s: %s\n", c.name, hand.adapter().message());
  hand.run(0.3);
  EXPECT_FALSE(hand.reset_and_recover(0.4, 0.3)) << c.name << ": recovered while the cause persists";
  c.clear(hand);
  hand.run(0.6);
  ASSERT_TRUE(hand.reset_and_recover(0.6)) << c.name << ": " << hand.adapter().message();
  hand.command(0.6);
  hand.run(0.8);
  EXPECT_NEAR(hand.adapter().feedback().position_rad[c.motor], 0.6, 0.01) << c.name;
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kOperational) << c.name << ": " << hand.adapter().message();
}

TEST(HandAdapterVcan, MissingHeartbeatHoldsAndRecovers) {
  fault_and_recovery({"heartbeat of node 4", 3, hand_fault::kHeartbeat,
                      [](HandOnVcan& h) { ASSERT_TRUE(h.inject(4, drive::drive_od::inject::kSuppressHeartbeat, 1)); },
                      [](HandOnVcan& h) { ASSERT_TRUE(h.inject(4, drive::drive_od::inject::kSuppressHeartbeat, 0)); }});
}

TEST(HandAdapterVcan, PdoTimeoutHoldsAndRecovers) {
  fault_and_recovery({"TPDOs of node 6 dropped", 5, hand_fault::kStalePdo,
                      [](HandOnVcan& h) {
                        ASSERT_TRUE(h.inject(6, drive::drive_od::inject::kDropTpdos, drive::EmulatedDrive::kDropForever));
                      },
                      [](HandOnVcan& h) { ASSERT_TRUE(h.inject(6, drive::drive_od::inject::kDropTpdos, 0)); }});
}

TEST(HandAdapterVcan, BusOffErrorFrameHoldsAndRecovers) {
  // an error frame from cansend, as a controller driver would raise it; "restarted" ends it
  fault_and_recovery({"bus-off", 0, hand_fault::kBusOff,
                      [](HandOnVcan&) { ASSERT_TRUE(cansend("20000040#0000000000000000")); },
                      [](HandOnVcan&) { ASSERT_TRUE(cansend("20000100#0000000000000000")); }});
}

TEST(HandAdapterVcan, ErrorPassiveHoldsAndRecovers) {
  fault_and_recovery({"error passive", 8, hand_fault::kBusPassive,
                      [](HandOnVcan&) { ASSERT_TRUE(cansend("20000004#0010000000000000")); },
                      [](HandOnVcan&) { ASSERT_TRUE(cansend("20000100#0000000000000000")); }});
}

TEST(HandAdapterVcan, EmcyHoldsWithTheCodeAndRecovers) {
  HandOnVcan hand;
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  hand.command(0.4);
  hand.run(0.3);
  ASSERT_TRUE(hand.inject(7, drive::drive_od::inject::kRaiseFault, emcy::kOverCurrent));
  ASSERT_TRUE(hand.run_until_fault(6, hand_fault::kEmcy, 5.0)) << hand.adapter().message();
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kSafeHold);
  hand.run(0.1);
  const HandFeedback& fb = hand.adapter().feedback();
  EXPECT_NE(fb.faults[6] & hand_fault::kEmcy, 0u);
  EXPECT_NE(fb.faults[6] & hand_fault::kDrive, 0u);
  EXPECT_EQ(fb.error_code[6], emcy::kOverCurrent);
  ASSERT_TRUE(hand.reset_and_recover(0.5)) << hand.adapter().message();
  EXPECT_EQ(hand.adapter().feedback().error_code[6], 0u);
}

TEST(HandAdapterVcan, StalledMotorEndsInFollowingErrorAndRecovers) {
  HandOnVcan hand;
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  hand.command(0.2);
  hand.run(0.5);
  ASSERT_TRUE(hand.inject(3, drive::drive_od::inject::kStall, 1));
  hand.run(0.1);
  hand.command(0.8);  // the jammed motor cannot follow: following error after 0x6066 (100 ms)
  ASSERT_TRUE(hand.run_until([](const HandAdapter& a) { return a.feedback().error_code[2] == emcy::kFollowingError; },
                             5.0))
      << hand.adapter().message();
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kSafeHold);
  ASSERT_TRUE(hand.inject(3, drive::drive_od::inject::kStall, 0));
  ASSERT_TRUE(hand.reset_and_recover(0.5)) << hand.adapter().message();
}

TEST(HandAdapterVcan, SdoAbortHoldsWithTheAbortCodeAndRecovers) {
  HandOnVcan hand;
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  ASSERT_TRUE(hand.inject(2, drive::drive_od::inject::kRefuseSdo, 1));
  hand.command(0.4, false, 1.0);  // a new current limit goes out by SDO, node 2 aborts it
  ASSERT_TRUE(hand.run_until_fault(1, hand_fault::kSdo, 5.0)) << hand.adapter().message();
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kSafeHold);
  EXPECT_EQ(hand.adapter().feedback().sdo_abort_code[1], sdo_abort::kLocalControl);
  ASSERT_TRUE(hand.inject(2, drive::drive_od::inject::kRefuseSdo, 0));
  ASSERT_TRUE(hand.reset_and_recover(0.4)) << hand.adapter().message();
}

TEST(HandAdapterVcan, EmulatorCommandLineInjectsAScheduledFault) {
  // over-temperature in node 9, 3 s after the emulator started (the adapter is up by then)
  HandOnVcan hand(vm_config(), {"--inject", "3:9:emcy:0x4310"});
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  ASSERT_TRUE(hand.run_until([](const HandAdapter& a) { return a.feedback().error_code[8] == 0x4310; }, 10.0))
      << hand.adapter().message();
  EXPECT_EQ(hand.adapter().phase(), HandPhase::kSafeHold);
  ASSERT_TRUE(hand.reset_and_recover(0.3)) << hand.adapter().message();
}

TEST(HandAdapterVcan, BootTimeoutNamesTheMissingNode) {
  HandAdapterConfig config = vm_config();
  config.boot_timeout_s = 1.0;
  HandOnVcan hand(config, {"--nodes", "1-8"});
  ASSERT_TRUE(hand.run_until(HandPhase::kFailed, 10.0));
  EXPECT_NE(std::string(hand.adapter().message()).find("no boot-up or heartbeat from node 9 (Finger_Spread)"),
            std::string::npos)
      << hand.adapter().message();
}

// candump, an independent peer, sees our SYNC, the packed targets and the drives' TPDOs, sent
// on the configured 4 ms schedule
TEST(HandAdapterVcan, CandumpSeesSyncAndPdosOnTheConfiguredSchedule) {
  HandOnVcan hand;
  ASSERT_NO_FATAL_FAILURE(expect_operational(hand));
  const std::string cmd = "timeout 20 candump -L -n 1500 " + iface() + ",080:7FF,301:7FF,181:7FF";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::atomic<bool> done{false};
  std::vector<std::string> lines;
  std::thread reader([&] {
    char line[256];
    while (std::fgets(line, sizeof line, pipe) != nullptr) lines.emplace_back(line);
    done = true;
  });
  const int64_t start = monotonic_ns();
  const uint64_t syncs_before = hand.adapter().stats().syncs_sent;
  const uint64_t skipped_before = hand.skipped();
  while (!done && monotonic_ns() < start + 15'000'000'000LL) hand.cycle();
  const double elapsed_s = static_cast<double>(monotonic_ns() - start) * 1e-9;
  const auto sent = static_cast<double>(hand.adapter().stats().syncs_sent - syncs_before);
  const auto skipped = static_cast<double>(hand.skipped() - skipped_before);
  reader.join();
  ::pclose(pipe);
  // "(1700000000.123456) vcan0 080#" -> time and id
  std::vector<double> sync_t;
  std::vector<double> tpdo_t;
  size_t targets = 0;
  for (const std::string& l : lines) {
    const auto id = l.find(iface() + " ");
    if (l.size() < 3 || id == std::string::npos) continue;
    const std::string cob = l.substr(id + iface().size() + 1, 3);
    const double t = std::stod(l.substr(1));
    if (cob == "080") sync_t.push_back(t);
    if (cob == "301") ++targets;
    if (cob == "181") tpdo_t.push_back(t);
  }
  ASSERT_GT(sync_t.size(), 100u) << lines.size() << " lines";
  ASSERT_FALSE(tpdo_t.empty());
  const double rate_hz = static_cast<double>(sync_t.size() - 1) / (sync_t.back() - sync_t.front());
  // the median interval shows how regular the SYNC is: under TCG the guest's timer wakes the
  // loop late, it catches up with SYNCs close together (see docs/hand_adapter.md)
  std::vector<double> intervals;
  for (size_t i = 1; i < sync_t.size(); ++i) intervals.push_back(sync_t[i] - sync_t[i - 1]);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  const double median_period_ms = intervals[intervals.size() / 2] * 1e3;
  // the emulator answers each SYNC with a TPDO, a little later: compare up to its last answer
  const auto answered = static_cast<size_t>(std::count_if(sync_t.begin(), sync_t.end(),
                                                          [&](double t) { return t <= tpdo_t.back(); }));
  const double own_rate_hz = sent / elapsed_s;
  std::printf("candump: %zu SYNC, median period %.3f ms, mean rate %.1f Hz; %zu target RPDOs (0x301), "
              "%zu TPDOs of node 1 for %zu SYNC; the loop sent %.0f SYNC in %.3f s (%.1f Hz), %.0f deadlines "
              "dropped after stalls\n",
              sync_t.size(), median_period_ms, rate_hz, targets, tpdo_t.size(), answered, sent, elapsed_s,
              own_rate_hz, skipped);
  RecordProperty("sync_rate_hz", std::to_string(rate_hz));
  RecordProperty("sync_median_period_ms", std::to_string(median_period_ms));
  // the loop keeps the 4 ms schedule: every deadline of the window was either a SYNC or dropped
  // after a stall (the VM's, not the loop's: the host is shared)
  EXPECT_NEAR((sent + skipped) / elapsed_s, 250.0, 25.0);
  // candump's own rate is reported, not asserted: its window is a part of the loop's, and
  // on a loaded host the starved VM drops deadlines in one part more than in another
  // every SYNC is followed by the pair's target frame and answered by node 1's TPDO
  EXPECT_NEAR(static_cast<double>(targets), static_cast<double>(sync_t.size()), 2.0);
  // node 1 answers SYNCs, one TPDO each (at the start of the dump the emulator may still be
  // answering SYNCs from before it: it lags by a few cycles in the VM, more on a loaded host),
  // and it answers throughout: TPDOs in every tenth of the dump's SYNCs. What share it answers is
  // reported, not asserted: a starved VM's emulator finds its transmit queue full now and then
  EXPECT_LE(tpdo_t.size(), answered + 10);
  for (size_t tenth = 0; tenth < 10; ++tenth) {
    const double from = sync_t[tenth * sync_t.size() / 10];
    const double to = sync_t[std::min(sync_t.size() - 1, (tenth + 1) * sync_t.size() / 10)];
    EXPECT_TRUE(std::any_of(tpdo_t.begin(), tpdo_t.end(), [&](double t) { return t > from && t <= to; }))
        << "no TPDO of node 1 between SYNCs at " << from << " and " << to << " s";
  }
}

}  // namespace
}  // namespace teleop::hand
