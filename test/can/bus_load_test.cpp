// Bus-load arithmetic: frame lengths with and without stuff bits, and loads of periodic traffic.
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

}  // namespace
}  // namespace teleop::can
