// SocketCanBus on this host. The kernel here has no AF_CAN, so opening must fail with an error
// that names the interface and the cause; on a host with CAN, a missing interface must fail the
// same way naming the interface. The bus itself is tested on vcan by test/vcan (in a VM).
#include "teleop/can/socketcan_bus.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>
#include <linux/can.h>

#include <cerrno>
#include <string>

namespace teleop::can {
namespace {

bool host_has_af_can() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

TEST(SocketCanBus, OpenFailsWithClearErrorNamingTheInterface) {
  try {
    SocketCanBus bus("teleopcan7");
    FAIL() << "opening a non-existent CAN interface succeeded";
  } catch (const SocketCanError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("teleopcan7"), std::string::npos) << what;
    if (!host_has_af_can()) {
      EXPECT_EQ(e.error(), EAFNOSUPPORT);
      EXPECT_NE(what.find("ddress family not supported"), std::string::npos) << what;
    } else {
      EXPECT_EQ(e.error(), ENODEV) << what;
    }
  }
}

TEST(SocketCanBus, RejectsInvalidInterfaceNames) {
  EXPECT_THROW(SocketCanBus(""), SocketCanError);
  EXPECT_THROW(SocketCanBus("a_name_longer_than_ifnamsiz"), SocketCanError);
}

TEST(SocketCanBus, CanopenNodeFiltersCoverBroadcastAndTheNodesOwnIds) {
  const auto f = canopen_node_filters(5);
  auto has = [&](uint32_t id) {
    for (const auto& x : f)
      if ((id & x.mask) == (x.id & x.mask)) return true;
    return false;
  };
  EXPECT_TRUE(has(0x000));  // NMT
  EXPECT_TRUE(has(0x080));  // SYNC
  EXPECT_TRUE(has(0x605));  // SDO request
  EXPECT_TRUE(has(0x205));
  EXPECT_TRUE(has(0x505));
  EXPECT_FALSE(has(0x606));  // another node's SDO
  EXPECT_FALSE(has(0x185));  // its own TPDO
  EXPECT_FALSE(has(0x585));  // its own SDO response
}

}  // namespace
}  // namespace teleop::can
