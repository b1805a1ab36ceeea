// The doctor's readers on a tree of files made to look like another host's /proc, /sys, /dev and
// /etc, and on `ip -json` answers (doctor/host_reader.h).
#include <grp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>

#include "process_helpers.h"
#include "teleop/doctor/host_reader.h"

namespace teleop::doctor {
namespace {

namespace fs = std::filesystem;

class FakeHost : public ::testing::Test {
 protected:
  void put(const std::string& relative, const std::string& text) {
    const fs::path path = fs::path(root) / relative;
    fs::create_directories(path.parent_path());
    test::write_file(path.string(), text);
  }
  std::string root = test::make_temp_dir();
};

TEST_F(FakeHost, GovernorsAreReadInCpuOrderAndCpusWithoutCpufreqLeftOut) {
  put("sys/devices/system/cpu/cpu10/cpufreq/scaling_governor", "powersave\n");
  put("sys/devices/system/cpu/cpu2/cpufreq/scaling_governor", "performance\n");
  put("sys/devices/system/cpu/cpu1/online", "1\n");  // no cpufreq
  put("sys/devices/system/cpu/cpufreq/policy0/scaling_governor", "schedutil\n");  // not a CPU
  EXPECT_EQ(read_governors(root), (std::vector<std::string>{"performance", "powersave"}));
  EXPECT_TRUE(read_governors(root + "/nothing").empty());
}

TEST_F(FakeHost, TheRealtimeFlagAndThePreemptionModelComeFromSys) {
  EXPECT_FALSE(read_kernel(root).realtime_flag);
  put("sys/kernel/realtime", "1\n");
  put("sys/kernel/debug/sched/preempt", "none voluntary (full) lazy\n");
  const KernelFacts k = read_kernel(root);
  EXPECT_TRUE(k.realtime_flag);
  EXPECT_EQ(k.preemption, "full");
  EXPECT_FALSE(k.release.empty()) << "uname";
}

TEST_F(FakeHost, TimeDaemonsAreFoundByTheirProcessNames) {
  put("proc/1/comm", "systemd\n");
  put("proc/412/comm", "chronyd\n");
  put("proc/413/comm", "systemd-timesyn\n");  // cut at 15 characters by the kernel
  put("proc/self/comm", "ptp4l\n");           // not a process number
  put("proc/sys/comm", "ntpd\n");
  EXPECT_EQ(read_time_daemons(root), (std::vector<std::string>{"chronyd", "systemd-timesyncd"}));
}

TEST_F(FakeHost, InputDevicesCarryTheirNamesGroupsAndAccess) {
  put("dev/input/event10", "");
  put("dev/input/event2", "");
  put("dev/input/mice", "");  // not an event device
  put("sys/class/input/event2/device/name", "3Dconnexion SpaceMouse Compact\n");
  const std::vector<InputDeviceFacts> devices = read_input_devices(root);
  ASSERT_EQ(devices.size(), 2u);
  EXPECT_EQ(devices[0].path, root + "/dev/input/event2");
  EXPECT_EQ(devices[0].name, "3Dconnexion SpaceMouse Compact");
  EXPECT_EQ(devices[1].name, "") << "no name in sys";
  EXPECT_TRUE(devices[0].readable);
  EXPECT_TRUE(devices[0].writable);
  const group* g = ::getgrgid(::getegid());
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(devices[0].group, g->gr_name);
}

TEST_F(FakeHost, ProvisioningFilesAreFoundWhereverDebianKeepsThem) {
  EXPECT_FALSE(read_provisioning(root).limits_file);
  put("etc/security/limits.d/95-teleop.conf", "@teleop - rtprio 95\n");
  put("lib/udev/rules.d/60-teleop.rules", "");
  put("etc/systemd/system/teleop-node@.service", "");
  const ProvisioningFacts p = read_provisioning(root);
  EXPECT_TRUE(p.limits_file);
  EXPECT_TRUE(p.udev_rules);
  EXPECT_TRUE(p.node_unit);
  EXPECT_FALSE(p.user.empty());
}

// as iproute2 6.1 prints them (ip -details -json link show dev ...)
constexpr const char* kCanUp =
    R"([{"ifindex":4,"ifname":"can0","flags":["NOARP","UP","LOWER_UP","ECHO"],"mtu":16,"qdisc":"pfifo_fast",)"
    R"("operstate":"UP","linkmode":"DEFAULT","group":"default","txqlen":10,"link_type":"can","promiscuity":0,)"
    R"("min_mtu":0,"max_mtu":0,"linkinfo":{"info_kind":"can","info_data":{"ctrlmode":["ONE-SHOT"],)"
    R"("state":"ERROR-ACTIVE","berr_counter":{"tx":0,"rx":0},"restart_ms":100,"bittiming":{"bitrate":500000,)"
    R"("sample_point":"0.875","tq":125,"prop_seg":6,"phase_seg1":7,"phase_seg2":2,"sjw":1,"brp":10},)"
    R"("clock":80000000}},"num_tx_queues":1,"num_rx_queues":1}])";
constexpr const char* kVcanDown =
    R"([{"ifindex":3,"ifname":"vcan0","flags":["NOARP"],"mtu":72,"operstate":"DOWN","link_type":"can",)"
    R"("linkinfo":{"info_kind":"vcan"}}])";

TEST(IpLink, ACanInterfaceGivesItsKindStateAndBitrate) {
  const CanLink can = parse_ip_link("can0", kCanUp);
  EXPECT_TRUE(can.exists);
  EXPECT_TRUE(can.up);
  EXPECT_EQ(can.kind, "can");
  EXPECT_EQ(can.bitrate_bps, 500000u);
  EXPECT_EQ(can.state, "ERROR-ACTIVE");
  const CanLink vcan = parse_ip_link("vcan0", kVcanDown);
  EXPECT_TRUE(vcan.exists);
  EXPECT_FALSE(vcan.up);
  EXPECT_EQ(vcan.kind, "vcan");
  EXPECT_EQ(vcan.bitrate_bps, 0u);
}

TEST(IpLink, NoAnswerIsNoInterfaceAndGarbageIsAnError) {
  EXPECT_FALSE(parse_ip_link("can7", "").exists);
  EXPECT_FALSE(parse_ip_link("can7", kCanUp).exists) << "another interface's answer";
  EXPECT_THROW(parse_ip_link("can0", "Device \"can0\" does not exist."), std::runtime_error);
  const CanLink odd = read_can_link("can0; reboot");  // never handed to a shell: ip's own error
  EXPECT_FALSE(odd.exists);
}

TEST(IpLink, TheRealIpSaysLoopbackIsNoCanInterface) {
  const CanLink lo = read_can_link("lo");
  EXPECT_TRUE(lo.exists);
  EXPECT_NE(lo.kind, "can");
  EXPECT_FALSE(read_can_link("nocan7").exists);
}

}  // namespace
}  // namespace teleop::doctor
