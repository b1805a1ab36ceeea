// Tick / radian / ampere conversions of one drive channel.
#include "teleop/hand/motor_channel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "allocation_counter.h"

namespace teleop::hand {

using namespace can;  // the CANopen core the hand is built on
namespace {

MotorChannelConfig geared() {
  MotorChannelConfig c;
  c.ticks_per_rev = 4096;
  c.gear_ratio = 100;
  c.rated_current_a = 1.5;
  return c;
}

TEST(MotorChannel, ConvertsOneOutputRevolutionOfTicksToTwoPi) {
  const MotorChannel ch(geared());
  EXPECT_NEAR(ch.ticks_to_rad(409600), 2 * M_PI, 1e-12);
  EXPECT_NEAR(ch.ticks_to_rad(-102400), -M_PI / 2, 1e-12);
  EXPECT_NEAR(ch.rad_per_tick(), 2 * M_PI / 409600, 1e-18);
  EXPECT_EQ(*ch.rad_to_ticks(M_PI), 204800);
}

TEST(MotorChannel, NegativeSignFlipsDirection) {
  MotorChannelConfig c = geared();
  c.sign = -1;
  const MotorChannel ch(c);
  EXPECT_NEAR(ch.ticks_to_rad(409600), -2 * M_PI, 1e-12);
  EXPECT_EQ(*ch.rad_to_ticks(M_PI / 2), -102400);
  EXPECT_NEAR(ch.ticks_per_s_to_radps(4096), -2 * M_PI / 100, 1e-12);
  EXPECT_NEAR(ch.permille_to_amps(200), -0.3, 1e-12);
}

TEST(MotorChannel, OffsetIsTheAngleAtTickZero) {
  MotorChannelConfig c = geared();
  c.offset_rad = 0.25;
  c.sign = -1;
  const MotorChannel ch(c);
  EXPECT_DOUBLE_EQ(ch.ticks_to_rad(0), 0.25);
  EXPECT_EQ(*ch.rad_to_ticks(0.25), 0);
  EXPECT_NEAR(ch.ticks_to_rad(-102400), 0.25 + M_PI / 2, 1e-12);
  EXPECT_EQ(*ch.rad_to_ticks(0.25 + M_PI / 2), -102400);
}

TEST(MotorChannel, RoundTripsWithinHalfATick) {
  MotorChannelConfig c = geared();
  c.offset_rad = -0.3;
  c.sign = -1;
  const MotorChannel ch(c);
  for (double q = -1.0; q <= 1.5; q += 0.0137) {
    const auto ticks = ch.rad_to_ticks(q);
    ASSERT_TRUE(ticks.ok());
    EXPECT_LE(std::fabs(ch.ticks_to_rad(*ticks) - q), 0.5 * ch.rad_per_tick() + 1e-12);
  }
  for (int32_t t : {-1000000, -1, 0, 1, 123456}) EXPECT_EQ(*ch.rad_to_ticks(ch.ticks_to_rad(t)), t);
}

TEST(MotorChannel, RejectsNanInfAndAnglesBeyondInt32) {
  const MotorChannel ch(geared());
  EXPECT_EQ(ch.rad_to_ticks(std::nan("")).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(ch.rad_to_ticks(std::numeric_limits<double>::infinity()).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(ch.rad_to_ticks(1e5).error(), CanError::kValueOutOfRange);  // 6.5e9 ticks
  EXPECT_EQ(ch.radps_to_ticks_per_s(std::nan("")).error(), CanError::kValueOutOfRange);
}

TEST(MotorChannel, ConvertsVelocityAndCurrent) {
  const MotorChannel ch(geared());
  EXPECT_NEAR(ch.ticks_per_s_to_radps(409600), 2 * M_PI, 1e-12);
  EXPECT_EQ(*ch.radps_to_ticks_per_s(M_PI), 204800);
  EXPECT_NEAR(ch.permille_to_amps(1000), 1.5, 1e-12);
  EXPECT_NEAR(ch.permille_to_amps(-500), -0.75, 1e-12);
  EXPECT_EQ(*ch.amps_to_max_current_permille(0.75), 500);
  EXPECT_EQ(*ch.amps_to_max_current_permille(0.0), 0);
  EXPECT_EQ(ch.amps_to_max_current_permille(-0.1).error(), CanError::kValueOutOfRange);
  EXPECT_EQ(ch.amps_to_max_current_permille(1e5).error(), CanError::kValueOutOfRange);
}

TEST(MotorChannel, RejectsInvalidConfiguration) {
  auto make = [](auto edit) {
    MotorChannelConfig c;
    edit(c);
    return MotorChannel(c);
  };
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.ticks_per_rev = 0; }), std::invalid_argument);
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.gear_ratio = -2; }), std::invalid_argument);
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.sign = 0; }), std::invalid_argument);
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.sign = 2; }), std::invalid_argument);
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.offset_rad = std::nan(""); }), std::invalid_argument);
  EXPECT_THROW(make([](MotorChannelConfig& c) { c.rated_current_a = 0; }), std::invalid_argument);
  EXPECT_NO_THROW(make([](MotorChannelConfig& c) { c.sign = -1; }));
}

TEST(MotorChannel, ConversionsDoNotAllocate) {
  const MotorChannel ch(geared());
  test::ScopedAllocationCounter counter;
  double sum = 0;
  for (int i = 0; i < 100; ++i) sum += ch.ticks_to_rad(*ch.rad_to_ticks(0.01 * i));
  EXPECT_GT(sum, 0);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::hand
