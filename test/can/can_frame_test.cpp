// CanFrame and its conversion to and from SocketCAN's struct can_frame.
#include "teleop/can/can_frame.h"

#include <gtest/gtest.h>
#include <linux/can/error.h>

#include "allocation_counter.h"

namespace teleop::can {
namespace {

CanFrame frame(uint32_t id, std::initializer_list<uint8_t> bytes, uint8_t flags = 0) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  for (uint8_t b : bytes) f.data[f.dlc++] = b;
  return f;
}

TEST(CanFrame, ConvertsStandardFrameToLinuxAndBack) {
  const CanFrame f = frame(0x181, {1, 2, 3, 4, 5, 6, 7, 8});
  const auto linux_frame = to_linux(f);
  ASSERT_TRUE(linux_frame.ok());
  EXPECT_EQ(linux_frame->can_id, 0x181u);
  EXPECT_EQ(linux_frame->len, 8);
  EXPECT_EQ(linux_frame->data[0], 1);
  EXPECT_EQ(linux_frame->data[7], 8);
  const auto back = from_linux(*linux_frame);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, f);
}

TEST(CanFrame, ConvertsExtendedRtrAndErrorFlagsToCanIdBits) {
  const auto ext = to_linux(frame(0x1ABCDEF0, {0xAA}, CanFrame::kExtended));
  ASSERT_TRUE(ext.ok());
  EXPECT_EQ(ext->can_id, 0x1ABCDEF0u | CAN_EFF_FLAG);
  const auto rtr = to_linux(frame(0x701, {}, CanFrame::kRtr));
  ASSERT_TRUE(rtr.ok());
  EXPECT_EQ(rtr->can_id, 0x701u | CAN_RTR_FLAG);

  can_frame err{};
  err.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
  err.len = CAN_ERR_DLC;
  const auto e = from_linux(err);
  ASSERT_TRUE(e.ok());
  EXPECT_TRUE(e->error());
  EXPECT_EQ(e->id, static_cast<uint32_t>(CAN_ERR_BUSOFF));
  for (const CanFrame& f : {frame(0x1ABCDEF0, {1}, CanFrame::kExtended), frame(0x701, {}, CanFrame::kRtr), *e}) {
    const auto l = to_linux(f);
    ASSERT_TRUE(l.ok());
    const auto round = from_linux(*l);
    ASSERT_TRUE(round.ok());
    EXPECT_EQ(*round, f);
  }
}

// found by the fuzzer: an error frame with the extended or RTR bit did not convert back to itself
TEST(CanFrame, ErrorFrameCarriesNoOtherFlag) {
  EXPECT_FALSE(frame(CAN_ERR_BUSOFF, {}, CanFrame::kError | CanFrame::kExtended).valid());
  EXPECT_FALSE(frame(CAN_ERR_BUSOFF, {}, CanFrame::kError | CanFrame::kRtr).valid());
  EXPECT_EQ(to_linux(frame(CAN_ERR_BUSOFF, {}, CanFrame::kError | CanFrame::kExtended)).error(), CanError::kInvalidId);
  can_frame err{};
  err.can_id = CAN_ERR_FLAG | CAN_RTR_FLAG | CAN_ERR_RESTARTED;
  const auto e = from_linux(err);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->flags, CanFrame::kError);
}

TEST(CanFrame, RejectsLinuxFrameWithLenAboveEight) {
  can_frame f{};
  f.can_id = 0x123;
  f.len = 9;
  EXPECT_EQ(from_linux(f).error(), CanError::kInvalidDlc);
}

TEST(CanFrame, RejectsStandardLinuxFrameWithIdAbove11Bits) {
  can_frame f{};
  f.can_id = 0x800;
  f.len = 0;
  EXPECT_EQ(from_linux(f).error(), CanError::kInvalidId);
}

TEST(CanFrame, RefusesToConvertInvalidFrameToLinux) {
  CanFrame long_frame = frame(0x100, {});
  long_frame.dlc = 9;
  EXPECT_EQ(to_linux(long_frame).error(), CanError::kInvalidDlc);
  EXPECT_EQ(to_linux(frame(0x800, {})).error(), CanError::kInvalidId);
  EXPECT_EQ(to_linux(frame(0x20000000, {}, CanFrame::kExtended)).error(), CanError::kInvalidId);
  EXPECT_EQ(to_linux(frame(0x100, {}, 0x80)).error(), CanError::kInvalidField);
}

TEST(CanFrame, ValidChecksIdRangeOfItsFormat) {
  EXPECT_TRUE(frame(0x7FF, {}).valid());
  EXPECT_FALSE(frame(0x800, {}).valid());
  EXPECT_TRUE(frame(0x800, {}, CanFrame::kExtended).valid());
  EXPECT_TRUE(frame(0x1FFFFFFF, {}, CanFrame::kExtended).valid());
  EXPECT_FALSE(frame(0x20000000, {}, CanFrame::kExtended).valid());
}

TEST(CanFrame, ComparesOnlyDataWithinDlc) {
  CanFrame a = frame(0x200, {1, 2});
  CanFrame b = a;
  b.data[5] = 99;  // beyond dlc: no difference
  EXPECT_EQ(a, b);
  b.data[1] = 3;
  EXPECT_FALSE(a == b);
  b = a;
  b.flags = CanFrame::kRtr;
  EXPECT_FALSE(a == b);
}

TEST(CanFrame, ResultHoldsValueOrError) {
  const Result<int> good(7);
  EXPECT_TRUE(good.ok());
  EXPECT_EQ(*good, 7);
  const Result<int> bad(CanError::kInvalidDlc);
  EXPECT_FALSE(bad.ok());
  EXPECT_FALSE(static_cast<bool>(bad));
  EXPECT_EQ(bad.error(), CanError::kInvalidDlc);
  EXPECT_STREQ(to_string(bad.error()), "invalid dlc");
}

TEST(CanFrame, LinuxConversionDoesNotAllocate) {
  const CanFrame f = frame(0x181, {1, 2, 3, 4, 5, 6, 7, 8});
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 100; ++i) {
    const auto l = to_linux(f);
    const auto back = from_linux(*l);
    ASSERT_TRUE(back.ok());
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::can
