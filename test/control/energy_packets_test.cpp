#include "teleop/control/energy_packets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "test_helpers.h"

namespace teleop::control {
namespace {

EnergyPacket packet(std::uint64_t seq, double in0, double in1) {
  EnergyPacket p;
  p.seq = seq;
  p.channels = 2;
  p.energy_in_j[0] = in0;
  p.energy_in_j[1] = in1;
  p.energy_out_j[0] = 0.5 * in0;
  return p;
}

TEST(RemoteEnergy, IgnoresDuplicatesAndReorderedPackets) {
  RemoteEnergy remote(2);
  EXPECT_EQ(remote.receive(packet(1, 0.1, 0.2)), PacketVerdict::kAccepted);
  EXPECT_EQ(remote.receive(packet(3, 0.3, 0.4)), PacketVerdict::kAccepted);
  // seq 2 arrives after 3 with smaller totals, then 3 again, then 5 before 4
  EXPECT_EQ(remote.receive(packet(2, 0.2, 0.3)), PacketVerdict::kStale);
  EXPECT_EQ(remote.receive(packet(3, 0.3, 0.4)), PacketVerdict::kStale);
  EXPECT_EQ(remote.receive(packet(5, 0.5, 0.6)), PacketVerdict::kAccepted);
  EXPECT_EQ(remote.receive(packet(4, 0.4, 0.5)), PacketVerdict::kStale);
  EXPECT_EQ(remote.last_seq(), 5u);
  EXPECT_EQ(remote.energy_in_j(0), 0.5);
  EXPECT_EQ(remote.energy_in_j(1), 0.6);
  EXPECT_EQ(remote.counters().accepted, 3u);
  EXPECT_EQ(remote.counters().stale, 3u);
  // 2 and 4 were never used
  EXPECT_EQ(remote.counters().missed, 2u);
  EXPECT_EQ(remote.counters().invalid, 0u);
}

TEST(RemoteEnergy, RejectsInvalidPacketsAndKeepsTheLastTotals) {
  RemoteEnergy remote(2);
  ASSERT_EQ(remote.receive(packet(1, 1.0, 1.0)), PacketVerdict::kAccepted);
  EnergyPacket wrong_channels = packet(2, 2.0, 2.0);
  wrong_channels.channels = 3;
  EXPECT_EQ(remote.receive(wrong_channels), PacketVerdict::kInvalid);
  EXPECT_EQ(remote.receive(packet(3, std::nan(""), 2.0)), PacketVerdict::kInvalid);
  EXPECT_EQ(remote.receive(packet(4, 2.0, std::numeric_limits<double>::infinity())), PacketVerdict::kInvalid);
  EXPECT_EQ(remote.receive(packet(5, -1.0, 2.0)), PacketVerdict::kInvalid);
  // a newer packet whose input total went down: totals never decrease within a session
  EXPECT_EQ(remote.receive(packet(6, 0.9, 2.0)), PacketVerdict::kInvalid);
  EXPECT_EQ(remote.receive(packet(0, 2.0, 2.0)), PacketVerdict::kInvalid);
  EnergyPacket bad_out = packet(7, 2.0, 2.0);
  bad_out.energy_out_j[1] = std::nan("");
  EXPECT_EQ(remote.receive(bad_out), PacketVerdict::kInvalid);
  EXPECT_EQ(remote.counters().invalid, 7u);
  EXPECT_EQ(remote.last_seq(), 1u);
  EXPECT_EQ(remote.energy_in_j(0), 1.0);
  EXPECT_EQ(remote.energy_in_j(1), 1.0);
  EXPECT_EQ(remote.receive(packet(8, 3.0, 4.0)), PacketVerdict::kAccepted);
  EXPECT_EQ(remote.energy_in_j(1), 4.0);
}

TEST(RemoteEnergy, ResetStartsANewSession) {
  RemoteEnergy remote(2);
  ASSERT_EQ(remote.receive(packet(10, 1.0, 1.0)), PacketVerdict::kAccepted);
  remote.reset();
  EXPECT_EQ(remote.last_seq(), 0u);
  EXPECT_EQ(remote.energy_in_j(0), 0.0);
  EXPECT_EQ(remote.counters().accepted, 0u);
  EXPECT_EQ(remote.receive(packet(1, 0.1, 0.1)), PacketVerdict::kAccepted);
  // a sender whose numbers go on across sessions (the bus header's): nothing missed at the start
  remote.reset();
  EXPECT_EQ(remote.receive(packet(500, 0.1, 0.1)), PacketVerdict::kAccepted);
  EXPECT_EQ(remote.counters().missed, 0u);
  EXPECT_EQ(remote.receive(packet(502, 0.2, 0.2)), PacketVerdict::kAccepted);
  EXPECT_EQ(remote.counters().missed, 1u);
}

TEST(RemoteEnergy, RejectsAChannelCountOutOfRange) {
  EXPECT_NE(test::error_of<std::invalid_argument>([] { RemoteEnergy r(0); }).find("channels must be 1..16"),
            std::string::npos);
  EXPECT_NE(test::error_of<std::invalid_argument>([] { RemoteEnergy r(17); }).find("got 17"), std::string::npos);
}

}  // namespace
}  // namespace teleop::control
