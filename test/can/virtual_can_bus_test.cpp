// The in-memory CAN bus: delivery, ordering, timeouts, overruns, error states, threads.
#include "teleop/can/virtual_can_bus.h"

#include <gtest/gtest.h>
#include <linux/can/error.h>

#include <atomic>
#include <thread>
#include <vector>

#include "allocation_counter.h"
#include "teleop/can/cia301.h"

namespace teleop::can {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;

CanFrame frame(uint32_t id, uint8_t byte = 0) {
  CanFrame f;
  f.id = id;
  f.dlc = 1;
  f.data[0] = byte;
  return f;
}

std::vector<CanFrame> drain(VirtualCanEndpoint& ep) {
  std::vector<CanFrame> out;
  CanFrame f;
  while (ep.receive(f, nanoseconds::zero()) == CanStatus::kOk) out.push_back(f);
  return out;
}

TEST(VirtualCanBus, DeliversEveryFrameToAllOtherEndpointsButNotTheSender) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  auto b = bus.open("b");
  auto c = bus.open("c");
  EXPECT_EQ(bus.endpoints(), 3u);
  ASSERT_EQ(a->send(frame(0x100, 1)), CanStatus::kOk);
  EXPECT_EQ(a->pending(), 0u);
  const auto at_b = drain(*b);
  const auto at_c = drain(*c);
  ASSERT_EQ(at_b.size(), 1u);
  ASSERT_EQ(at_c.size(), 1u);
  EXPECT_EQ(at_b[0], frame(0x100, 1));
  EXPECT_EQ(at_c[0], frame(0x100, 1));
  EXPECT_TRUE(drain(*a).empty());
  EXPECT_EQ(a->stats().tx_frames, 1u);
  EXPECT_EQ(b->stats().rx_frames, 1u);
}

TEST(VirtualCanBus, KeepsOneGlobalOrderAcrossSenders) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  auto b = bus.open("b");
  auto monitor = bus.open("monitor");
  ASSERT_EQ(a->send(frame(0x100, 1)), CanStatus::kOk);
  ASSERT_EQ(b->send(frame(0x200, 2)), CanStatus::kOk);
  ASSERT_EQ(a->send(frame(0x100, 3)), CanStatus::kOk);
  const auto seen = drain(*monitor);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].data[0], 1);
  EXPECT_EQ(seen[1].data[0], 2);
  EXPECT_EQ(seen[2].data[0], 3);
  const auto at_a = drain(*a);  // a sees only b's frame
  ASSERT_EQ(at_a.size(), 1u);
  EXPECT_EQ(at_a[0].id, 0x200u);
}

TEST(VirtualCanBus, ReceiveTimesOutWhenNothingArrives) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  CanFrame f;
  EXPECT_EQ(a->receive(f, nanoseconds::zero()), CanStatus::kTimeout);
  EXPECT_EQ(a->receive(f, milliseconds(2)), CanStatus::kTimeout);
}

TEST(VirtualCanBus, ReceiveWakesUpWhenAnotherThreadSends) {
  VirtualCanBus bus;
  auto rx = bus.open("rx");
  auto tx = bus.open("tx");
  std::thread sender([&] {
    std::this_thread::sleep_for(milliseconds(5));
    ASSERT_EQ(tx->send(frame(0x123, 7)), CanStatus::kOk);
  });
  CanFrame f;
  const CanStatus status = rx->receive(f, std::chrono::seconds(10));
  sender.join();
  ASSERT_EQ(status, CanStatus::kOk);
  EXPECT_EQ(f, frame(0x123, 7));
}

TEST(VirtualCanBus, FullQueueDropsFramesAndCountsOverruns) {
  VirtualCanBus bus(4);
  auto tx = bus.open("tx");
  auto rx = bus.open("rx");
  for (uint8_t i = 0; i < 6; ++i) ASSERT_EQ(tx->send(frame(0x100, i)), CanStatus::kOk);
  EXPECT_EQ(rx->pending(), 4u);
  EXPECT_EQ(rx->stats().rx_overruns, 2u);
  const auto got = drain(*rx);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got.front().data[0], 0);  // the oldest are kept, the newest lost
  EXPECT_EQ(got.back().data[0], 3);
  // and the ring keeps working after wrapping
  for (uint8_t i = 10; i < 13; ++i) ASSERT_EQ(tx->send(frame(0x100, i)), CanStatus::kOk);
  const auto again = drain(*rx);
  ASSERT_EQ(again.size(), 3u);
  EXPECT_EQ(again[2].data[0], 12);
}

TEST(VirtualCanBus, RejectsInvalidFramesAndApplicationErrorFrames) {
  VirtualCanBus bus;
  auto tx = bus.open("tx");
  auto rx = bus.open("rx");
  CanFrame bad = frame(0x800);
  EXPECT_EQ(tx->send(bad), CanStatus::kInvalidFrame);
  bad = frame(0x100);
  bad.dlc = 9;
  EXPECT_EQ(tx->send(bad), CanStatus::kInvalidFrame);
  CanFrame error = frame(CAN_ERR_BUSOFF);
  error.flags = CanFrame::kError;
  EXPECT_EQ(tx->send(error), CanStatus::kInvalidFrame);
  EXPECT_EQ(rx->pending(), 0u);
  EXPECT_EQ(tx->stats().tx_dropped, 3u);
}

TEST(VirtualCanBus, BusOffEndpointCannotSendAndSeesErrorFrame) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  auto b = bus.open("b");
  a->set_state(CanBusState::kBusOff);
  EXPECT_EQ(a->state(), CanBusState::kBusOff);
  EXPECT_EQ(a->send(frame(0x100)), CanStatus::kBusOff);
  EXPECT_EQ(b->pending(), 0u);
  // the error frame SocketCAN would deliver
  CanFrame f;
  ASSERT_EQ(a->receive(f, nanoseconds::zero()), CanStatus::kOk);
  EXPECT_TRUE(f.error());
  EXPECT_EQ(f.id, static_cast<uint32_t>(CAN_ERR_BUSOFF));
  EXPECT_EQ(a->stats().error_frames, 1u);
  // a bus-off controller does not receive either
  ASSERT_EQ(b->send(frame(0x200)), CanStatus::kOk);
  EXPECT_EQ(a->pending(), 0u);
  // recovery
  a->set_state(CanBusState::kErrorActive);
  EXPECT_EQ(a->send(frame(0x100)), CanStatus::kOk);
  EXPECT_EQ(b->pending(), 1u);
}

TEST(VirtualCanBus, ClosedEndpointLeavesTheBus) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  auto b = bus.open("b");
  b.reset();
  EXPECT_EQ(bus.endpoints(), 1u);
  EXPECT_EQ(a->send(frame(0x100)), CanStatus::kOk);  // nobody listens: still fine
  // an endpoint may outlive the bus object
  std::unique_ptr<VirtualCanEndpoint> survivor;
  {
    VirtualCanBus temporary;
    survivor = temporary.open("survivor");
  }
  EXPECT_EQ(survivor->send(frame(0x100)), CanStatus::kOk);
}

TEST(VirtualCanBus, ConcurrentSendersLoseNothingAndKeepTheirOwnOrder) {
  constexpr int kFrames = 2000;
  VirtualCanBus bus(2 * kFrames);
  auto rx = bus.open("rx");
  auto a = bus.open("a");
  auto b = bus.open("b");
  auto send_all = [](VirtualCanEndpoint& ep, uint32_t id) {
    for (int i = 0; i < kFrames; ++i) {
      CanFrame f;
      f.id = id;
      f.dlc = 2;
      f.data[0] = static_cast<uint8_t>(i);
      f.data[1] = static_cast<uint8_t>(i >> 8);
      ASSERT_EQ(ep.send(f), CanStatus::kOk);
    }
  };
  std::thread ta(send_all, std::ref(*a), 0x100);
  std::thread tb(send_all, std::ref(*b), 0x200);
  ta.join();
  tb.join();
  int next_a = 0;
  int next_b = 0;
  for (const CanFrame& f : drain(*rx)) {
    const int n = f.data[0] | (f.data[1] << 8);
    if (f.id == 0x100) {
      EXPECT_EQ(n, next_a++);
    } else if (f.id == 0x200) {
      EXPECT_EQ(n, next_b++);
    }
  }
  EXPECT_EQ(next_a, kFrames);
  EXPECT_EQ(next_b, kFrames);
}

TEST(VirtualCanBus, SendAndReceiveDoNotAllocate) {
  VirtualCanBus bus;
  auto a = bus.open("a");
  auto b = bus.open("b");
  test::ScopedAllocationCounter counter;
  CanFrame f;
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(a->send(frame(0x100, static_cast<uint8_t>(i))), CanStatus::kOk);
    ASSERT_EQ(b->receive(f, nanoseconds::zero()), CanStatus::kOk);
  }
  EXPECT_EQ(b->receive(f, nanoseconds::zero()), CanStatus::kTimeout);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::can
