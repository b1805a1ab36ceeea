// The start-up's SDO client on a bus with other traffic: it hands the frames that are not its
// answer on, and a drive that never answers ends the wait at its timeout however busy the bus is.
#include "canopen_sdo_client.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "teleop/can/virtual_can_bus.h"

namespace teleop::robot {
namespace {

TEST(SdoClient, ANodeThatNeverAnswersTimesOutThoughTheBusNeverFallsSilent) {
  can::VirtualCanBus bus;
  auto master = bus.open("master");
  auto other = bus.open("other node");
  // another node's heartbeat, far faster than the client's poll, until the client gave up
  std::atomic<bool> done{false};
  std::thread chatter([&] {
    const auto heartbeat = can::encode_heartbeat(5, can::NmtState::kOperational);
    while (!done) {
      (void)other->send(*heartbeat);
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  });
  SdoWait wait;
  wait.poll = std::chrono::milliseconds(1);
  wait.timeout = std::chrono::milliseconds(30);
  SdoClient sdo(*master, wait);
  size_t others = 0;
  sdo.other_frames = [&](const can::CanFrame&) { ++others; };
  std::string error;
  try {
    (void)sdo.read(9, 0x1000, 0);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  done = true;
  chatter.join();
  EXPECT_EQ(error, "SDO node 9, 0x1000:00: no answer within 30 ms (is the drive on the bus, with this node id?)");
  EXPECT_GT(others, 0u) << "the heartbeats were handed on";
}

}  // namespace
}  // namespace teleop::robot
