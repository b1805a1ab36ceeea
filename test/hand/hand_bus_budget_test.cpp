// The hand's bus budget: the naive and the chosen plan against the bus, impossible plans, and
// one cycle of the plan sent on a VirtualCanBus counting the bits the budget predicts.
#include "teleop/hand/hand_bus_budget.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "teleop/can/cia301.h"
#include "teleop/can/virtual_can_bus.h"

namespace teleop::hand {
namespace {

using namespace can;  // the CANopen core the hand is built on

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

TEST(HandBusBudget, VirtualBusCountsTheBitsOfOneCycleOfThePlan) {
  VirtualCanBus bus;
  auto tx = bus.open("tx");
  auto rx = bus.open("rx");
  // one cycle of the chosen hand plan: SYNC, 4 packed RPDOs, 1 short RPDO, 9 TPDOs
  ASSERT_EQ(tx->send(*encode_sync()), CanStatus::kOk);
  CanFrame f;
  f.dlc = 8;
  for (int i = 0; i < 4; ++i) {
    f.id = 0x301 + 2 * i;
    ASSERT_EQ(tx->send(f), CanStatus::kOk);
  }
  f.dlc = 4;
  f.id = 0x309;
  ASSERT_EQ(tx->send(f), CanStatus::kOk);
  f.dlc = 8;
  for (int node = 1; node <= 9; ++node) {
    f.id = 0x180 + node;
    ASSERT_EQ(tx->send(f), CanStatus::kOk);
  }
  HandBusPlan plan;
  const HandBusBudget budget = hand_bus_budget(plan);
  const VirtualBusTraffic traffic = bus.traffic();
  EXPECT_EQ(traffic.frames, budget.frames_per_cycle);
  EXPECT_EQ(traffic.bits_nominal, budget.bits_per_cycle_nominal);
  EXPECT_EQ(traffic.bits_worst_case, budget.bits_per_cycle_worst_case);
}

}  // namespace
}  // namespace teleop::hand
