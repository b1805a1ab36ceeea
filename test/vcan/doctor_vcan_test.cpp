// `teleop doctor`'s CAN check against a kernel that has CAN (the VM's vcan interfaces): what
// `ip -details -json` reports of a real vcan, up and then down, judged as the doctor judges a
// configured bus (doctor/host_reader.h, doctor/checks.h).
#include <gtest/gtest.h>

#include <cstdlib>

#include "teleop/doctor/checks.h"
#include "teleop/doctor/host_reader.h"
#include "vcan_support.h"

namespace teleop::doctor {
namespace {

HostNeeds needing(const std::string& interface) {
  HostNeeds needs;
  needs.can.push_back({interface, 1e6, "hand", "hand.yaml"});
  return needs;
}

TEST(DoctorVcan, AVcanThatIsUpPassesAndOneTakenDownFailsWithItsFix) {
  const std::string bus = can::test::iface();
  const CanLink up = read_can_link(bus);
  EXPECT_TRUE(up.exists);
  EXPECT_TRUE(up.up);
  EXPECT_EQ(up.kind, "vcan");
  EXPECT_EQ(check_can({up}, needing(bus))[0].verdict, Verdict::kOk) << check_can({up}, needing(bus))[0].found;

  ASSERT_EQ(std::system(("ip link set " + bus + " down").c_str()), 0);
  const CanLink down = read_can_link(bus);
  ASSERT_EQ(std::system(("ip link set " + bus + " up").c_str()), 0);
  EXPECT_TRUE(down.exists);
  EXPECT_FALSE(down.up);
  const Finding finding = check_can({down}, needing(bus))[0];
  EXPECT_EQ(finding.verdict, Verdict::kFail);
  EXPECT_EQ(finding.fix, "sudo ip link set " + bus + " up");
  EXPECT_TRUE(read_can_link(bus).up) << "left as it was found";
}

TEST(DoctorVcan, LoopbackIsNoCanBusAndAMissingOneIsNamed) {
  const Finding lo = check_can({read_can_link("lo")}, needing("lo"))[0];
  EXPECT_EQ(lo.verdict, Verdict::kFail);
  EXPECT_NE(lo.found.find("not a CAN interface"), std::string::npos) << lo.found;
  const Finding missing = check_can({read_can_link("can9")}, needing("can9"))[0];
  EXPECT_EQ(missing.verdict, Verdict::kFail);
  EXPECT_NE(missing.found.find("no such interface"), std::string::npos) << missing.found;
}

}  // namespace
}  // namespace teleop::doctor
