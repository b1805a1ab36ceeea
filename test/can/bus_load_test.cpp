// Bus-load arithmetic: frame lengths with and without stuff bits, and the hand's budget.
#include "teleop/can/bus_load.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace teleop::can {
namespace {

TEST(BusLoad, StandardEightByteFrameIs111BitsWithoutStuffing) {
  EXPECT_EQ(frame_bits_nominal(8), 111u);
  EXPECT_EQ(frame_bits_nominal(0), 47u);
  EXPECT_EQ(frame_bits_nominal(8, CanIdFormat::kExtended), 131u);
  EXPECT_EQ(frame_bits_nominal(0, CanIdFormat::kExtended), 67u);
}

TEST(BusLoad, WorstCaseStuffingAddsOneBitPerFourAfterTheFirst) {
  // 47 + 8n + floor((34 + 8n - 1) / 4): 55 + 10 n for standard ids, 80 + 10 n for extended
  const uint32_t standard[] = {55, 65, 75, 85, 95, 105, 115, 125, 135};
  const uint32_t extended[] = {80, 90, 100, 110, 120, 130, 140, 150, 160};
  for (uint32_t n = 0; n <= 8; ++n) {
    EXPECT_EQ(frame_bits_worst_case(n), standard[n]) << n;
    EXPECT_EQ(frame_bits_worst_case(n, CanIdFormat::kExtended), extended[n]) << n;
  }
}

TEST(BusLoad, SumsPeriodicTraffic) {
  // 1000 eight-byte frames per second on 1 Mbit/s: 111 kbit/s nominal, 135 kbit/s worst case
  const Traffic t[] = {{10, 8, 100.0, CanIdFormat::kStandard}};
  const BusLoad load = bus_load(t, 1e6);
  EXPECT_DOUBLE_EQ(load.frames_per_s, 1000.0);
  EXPECT_DOUBLE_EQ(load.bits_per_s_nominal, 111000.0);
  EXPECT_DOUBLE_EQ(load.bits_per_s_worst_case, 135000.0);
  EXPECT_DOUBLE_EQ(load.load_nominal, 0.111);
  EXPECT_DOUBLE_EQ(load.load_worst_case, 0.135);
  EXPECT_FALSE(load.exceeds());
  EXPECT_TRUE(load.exceeds(0.1));
  // about 7400 (worst case) to 9000 (no stuffing) such frames fill a 1 Mbit/s bus
  EXPECT_NEAR(1e6 / frame_bits_worst_case(8), 7407, 1);
  EXPECT_NEAR(1e6 / frame_bits_nominal(8), 9009, 1);
}

TEST(BusLoad, NaivePlanOfNineteenFramesDoesNotFitOneKilohertz) {
  HandBusPlan naive;
  naive.cycle_rate_hz = 1000;
  naive.motors_per_rpdo = 1;
  naive.rpdo_bytes_per_motor = 6;  // controlword + target position
  naive.heartbeat_hz = 0;
  const HandBusBudget b = hand_bus_budget(naive);
  EXPECT_EQ(b.frames_per_cycle, 19u);
  EXPECT_EQ(b.bits_per_cycle_nominal, 47u + 9 * 95 + 9 * 111);      // 1901
  EXPECT_EQ(b.bits_per_cycle_worst_case, 55u + 9 * 115 + 9 * 135);  // 2305
  EXPECT_NEAR(b.load.load_nominal, 1.901, 1e-9);
  EXPECT_NEAR(b.load.load_worst_case, 2.305, 1e-9);
  EXPECT_TRUE(b.load.exceeds());
  // even at 500 Hz it does not fit
  naive.cycle_rate_hz = 500;
  EXPECT_GT(hand_bus_budget(naive).load.load_worst_case, 1.0);
}

TEST(BusLoad, ChosenPlanAt250HzStaysBelowHalfTheBus) {
  const HandBusPlan plan;  // the defaults are the plan of docs/can_bus_budget.md
  const HandBusBudget b = hand_bus_budget(plan);
  EXPECT_EQ(b.frames_per_cycle, 15u);                                    // SYNC + 5 RPDOs (4 x 2 targets + 1) + 9 TPDOs
  EXPECT_EQ(b.bits_per_cycle_nominal, 47u + 4 * 111 + 79 + 9 * 111);     // 1569
  EXPECT_EQ(b.bits_per_cycle_worst_case, 55u + 4 * 135 + 95 + 9 * 135);  // 1905
  EXPECT_NEAR(b.cycle_bus_time_worst_case_s, 1.905e-3, 1e-12);
  // with 9 heartbeats at 10 Hz: 1905 * 250 + 90 * 65 = 482100 bit/s
  EXPECT_NEAR(b.load.bits_per_s_worst_case, 482100.0, 1e-6);
  EXPECT_NEAR(b.load.load_worst_case, 0.4821, 1e-9);
  EXPECT_NEAR(b.load.load_nominal, (1569.0 * 250 + 90 * 55) / 1e6, 1e-9);
  EXPECT_FALSE(b.load.exceeds());
  EXPECT_NEAR(b.max_cycle_rate_hz, (700000.0 - 5850.0) / 1905.0, 1e-9);  // ~364 Hz
}

TEST(BusLoad, PackedPlanAt500HzExceedsSeventyPercent) {
  HandBusPlan plan;
  plan.cycle_rate_hz = 500;
  const HandBusBudget b = hand_bus_budget(plan);
  EXPECT_NEAR(b.load.load_worst_case, (1905.0 * 500 + 5850) / 1e6, 1e-9);  // 95.8 %
  EXPECT_TRUE(b.load.exceeds());
  EXPECT_GT(b.load.load_nominal, 0.70);  // even without stuff bits: 79 %
}

TEST(BusLoad, RejectsImpossiblePlans) {
  auto budget = [](auto edit) {
    HandBusPlan p;
    edit(p);
    return hand_bus_budget(p);
  };
  EXPECT_THROW(budget([](HandBusPlan& p) { p.motors = 0; }), std::invalid_argument);
  EXPECT_THROW(budget([](HandBusPlan& p) { p.cycle_rate_hz = 0; }), std::invalid_argument);
  EXPECT_THROW(budget([](HandBusPlan& p) { p.bitrate_bps = -1; }), std::invalid_argument);
  EXPECT_THROW(budget([](HandBusPlan& p) { p.motors_per_rpdo = 3; }), std::invalid_argument);  // 12 bytes
  EXPECT_THROW(budget([](HandBusPlan& p) { p.tpdo_bytes = 9; }), std::invalid_argument);
  EXPECT_THROW(budget([](HandBusPlan& p) { p.sync_bytes = 2; }), std::invalid_argument);
  EXPECT_NO_THROW(budget([](HandBusPlan& p) { p.sync_bytes = 1; }));
}

}  // namespace
}  // namespace teleop::can
