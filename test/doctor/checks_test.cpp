// Each of the doctor's checks on faked facts: what passes, what warns, what fails, and that a
// miss names its fix (doctor/checks.h).
#include <gtest/gtest.h>

#include "teleop/doctor/checks.h"

namespace teleop::doctor {
namespace {

HostNeeds asking(runtime::RealtimeMode mode, int priority = 80) {
  HostNeeds needs;
  runtime::RealtimeConfig realtime;
  realtime.mode = mode;
  realtime.priority = priority;
  needs.realtime.push_back({"follower", "follower.yaml", realtime});
  return needs;
}

HostNeeds needing_can(const std::string& interface, double bitrate) {
  HostNeeds needs;
  needs.can.push_back({interface, bitrate, "hand", "hand.yaml"});
  return needs;
}

TEST(DoctorKernel, APreemptRtKernelPassesAndAStockOneWarnsWithTheRtPackage) {
  EXPECT_EQ(check_kernel({"6.1.0-rt", "#1 SMP PREEMPT_RT Debian", false, ""}).verdict, Verdict::kOk);
  EXPECT_EQ(check_kernel({"6.1.0-rt", "#1 SMP", true, ""}).verdict, Verdict::kOk) << "/sys/kernel/realtime";
  const Finding stock = check_kernel({"6.1.0-13-amd64", "#1 SMP PREEMPT_DYNAMIC Debian", false, "voluntary"});
  EXPECT_EQ(stock.verdict, Verdict::kWarn);
  EXPECT_NE(stock.found.find("PREEMPT_DYNAMIC, voluntary"), std::string::npos) << stock.found;
  EXPECT_NE(stock.fix.find("linux-image-rt-amd64"), std::string::npos);
}

TEST(DoctorRtprio, ALimitBelowTheAskedPriorityFailsARequiredNodeAndWarnsAnOptionalOne) {
  SchedulingFacts s;
  s.rtprio_soft = 50;
  const Finding required = check_rtprio(s, asking(runtime::RealtimeMode::kRequired, 90));
  EXPECT_EQ(required.verdict, Verdict::kFail);
  EXPECT_NE(required.found.find("SCHED_FIFO 90"), std::string::npos) << required.found;
  EXPECT_NE(required.found.find("follower (required)"), std::string::npos) << required.found;
  EXPECT_NE(required.fix.find("usermod -aG teleop"), std::string::npos);
  EXPECT_EQ(check_rtprio(s, asking(runtime::RealtimeMode::kOptional, 90)).verdict, Verdict::kWarn);
  EXPECT_EQ(check_rtprio(s, HostNeeds{}).verdict, Verdict::kWarn) << "no config: judged at the default 80";
  s.rtprio_soft = 95;
  EXPECT_EQ(check_rtprio(s, asking(runtime::RealtimeMode::kRequired, 90)).verdict, Verdict::kOk);
}

TEST(DoctorRtprio, CapSysNicePassesAndATrialOnAThreadOverrulesTheLimit) {
  SchedulingFacts s;
  s.cap_sys_nice = true;
  EXPECT_EQ(check_rtprio(s, asking(runtime::RealtimeMode::kRequired)).verdict, Verdict::kOk);
  // a cgroup or a container may refuse what the limit allows: the thread's answer decides
  s.rtprio_soft = kUnlimited;
  s.fifo_trial = "Operation not permitted";
  s.fifo_trial_priority = 80;
  const Finding refused = check_rtprio(s, asking(runtime::RealtimeMode::kRequired));
  EXPECT_EQ(refused.verdict, Verdict::kFail);
  EXPECT_NE(refused.found.find("refused to a thread: Operation not permitted"), std::string::npos) << refused.found;
  // a trial at another priority than the one judged says nothing about it
  s.fifo_trial_priority = 10;
  EXPECT_EQ(check_rtprio(s, asking(runtime::RealtimeMode::kRequired)).verdict, Verdict::kOk);
}

TEST(DoctorMemlock, UnlimitedPassesAFewMegabytesFailARequiredNode) {
  SchedulingFacts s;
  s.memlock_soft = kUnlimited;
  EXPECT_EQ(check_memlock(s, asking(runtime::RealtimeMode::kRequired)).verdict, Verdict::kOk);
  s.memlock_soft = 8u << 20;  // Debian's default
  const Finding small = check_memlock(s, asking(runtime::RealtimeMode::kRequired));
  EXPECT_EQ(small.verdict, Verdict::kFail);
  EXPECT_NE(small.found.find("8388608 bytes"), std::string::npos) << small.found;
  EXPECT_EQ(check_memlock(s, asking(runtime::RealtimeMode::kOff)).verdict, Verdict::kWarn);
  s.cap_ipc_lock = true;
  EXPECT_EQ(check_memlock(s, asking(runtime::RealtimeMode::kRequired)).verdict, Verdict::kOk);
  s.cap_ipc_lock = false;
  s.memlock_soft = uint64_t{4} << 30;
  EXPECT_EQ(check_memlock(s, asking(runtime::RealtimeMode::kRequired)).verdict, Verdict::kWarn);
}

TEST(DoctorRtThrottling, TheKernelsDefaultPassesLessRealTimeTimeWarns) {
  SchedulingFacts s;
  EXPECT_EQ(check_rt_throttling(s).verdict, Verdict::kOk);
  s.rt_runtime_us = -1;
  EXPECT_EQ(check_rt_throttling(s).verdict, Verdict::kOk);
  s.rt_runtime_us = 500000;
  EXPECT_EQ(check_rt_throttling(s).verdict, Verdict::kWarn);
}

TEST(DoctorGovernor, PerformanceEverywherePassesOneSlowCpuWarns) {
  EXPECT_EQ(check_governors({}).verdict, Verdict::kOk) << "no cpufreq";
  EXPECT_EQ(check_governors({{"performance", "performance"}}).verdict, Verdict::kOk);
  const Finding slow = check_governors({{"performance", "powersave", "powersave"}});
  EXPECT_EQ(slow.verdict, Verdict::kWarn);
  EXPECT_NE(slow.found.find("powersave on 2 of 3 CPUs"), std::string::npos) << slow.found;
  EXPECT_NE(slow.fix.find("cpupower frequency-set -g performance"), std::string::npos);
}

TEST(DoctorClock, ASynchronisedClockPassesNamingItsDaemon) {
  const Finding synced = check_clock({true, 12000, 50, {"chronyd"}});
  EXPECT_EQ(synced.verdict, Verdict::kOk);
  EXPECT_NE(synced.found.find("chronyd"), std::string::npos);
  EXPECT_NE(synced.found.find("max error 12 ms"), std::string::npos) << synced.found;
  const Finding free_running = check_clock({false, 16000000, 0, {}});
  EXPECT_EQ(free_running.verdict, Verdict::kWarn);
  EXPECT_NE(free_running.found.find("no time daemon"), std::string::npos);
  EXPECT_NE(free_running.fix.find("chrony"), std::string::npos);
}

TEST(DoctorCan, AMissingOrDownBusFailsWithItsBringUp) {
  const auto missing = check_can({}, needing_can("can0", 1e6));
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].verdict, Verdict::kFail);
  EXPECT_EQ(missing[0].check, "can0");
  EXPECT_NE(missing[0].found.find("hand.yaml"), std::string::npos);
  const auto down = check_can({{"can0", true, "can", false, 0, "STOPPED", ""}}, needing_can("can0", 1e6));
  EXPECT_EQ(down[0].verdict, Verdict::kFail);
  EXPECT_NE(down[0].fix.find("sudo ip link set can0 type can bitrate 1000000"), std::string::npos) << down[0].fix;
  const auto not_can = check_can({{"can0", true, "veth", true, 0, "", ""}}, needing_can("can0", 1e6));
  EXPECT_EQ(not_can[0].verdict, Verdict::kFail);
  const auto no_ip = check_can({{"can0", false, "", false, 0, "", "Option \"-json\" is unknown"}}, needing_can("can0", 1e6));
  EXPECT_EQ(no_ip[0].verdict, Verdict::kFail);
  EXPECT_NE(no_ip[0].found.find("could not be looked at"), std::string::npos) << no_ip[0].found;
  EXPECT_NE(no_ip[0].found.find("-json"), std::string::npos) << no_ip[0].found;
}

TEST(DoctorCan, TheBitrateMustBeTheConfigsAndTheControllerOnTheBus) {
  const HostNeeds needs = needing_can("can0", 1e6);
  EXPECT_EQ(check_can({{"can0", true, "can", true, 1000000, "ERROR-ACTIVE", ""}}, needs)[0].verdict, Verdict::kOk);
  const auto slow = check_can({{"can0", true, "can", true, 500000, "ERROR-ACTIVE", ""}}, needs);
  EXPECT_EQ(slow[0].verdict, Verdict::kFail);
  EXPECT_NE(slow[0].found.find("500000 bit/s, the config plans 1000000"), std::string::npos) << slow[0].found;
  EXPECT_EQ(check_can({{"can0", true, "can", true, 1000000, "BUS-OFF", ""}}, needs)[0].verdict, Verdict::kFail);
  EXPECT_EQ(check_can({{"can0", true, "can", true, 1000000, "ERROR-PASSIVE", ""}}, needs)[0].verdict, Verdict::kWarn);
  EXPECT_EQ(check_can({{"can0", true, "vcan", true, 0, "", ""}}, needs)[0].verdict, Verdict::kOk) << "vcan has no bitrate";
}

TEST(DoctorInputDevices, OnlyTheDevicesTheRulesGrantAreJudged) {
  ProvisioningFacts p;
  p.user = "operator";
  const InputDeviceFacts keyboard{"/dev/input/event0", "AT keyboard", "input", false, false};
  InputDeviceFacts mouse{"/dev/input/event5", "3Dconnexion SpaceMouse Compact", "teleop", true, true};
  EXPECT_EQ(check_input_devices({keyboard}, p).verdict, Verdict::kOk) << "a keyboard is not the operator's device";
  const Finding usable = check_input_devices({keyboard, mouse}, p);
  EXPECT_EQ(usable.verdict, Verdict::kOk);
  EXPECT_NE(usable.found.find("SpaceMouse"), std::string::npos);
  mouse.writable = false;
  const Finding unusable = check_input_devices({keyboard, mouse}, p);
  EXPECT_EQ(unusable.verdict, Verdict::kWarn);
  EXPECT_NE(unusable.found.find("not usable by operator"), std::string::npos) << unusable.found;
  EXPECT_NE(unusable.fix.find("usermod -aG teleop operator"), std::string::npos);
}

TEST(DoctorDds, AWhitelistedAddressOnNoInterfaceFails) {
  const std::vector<NetworkInterfaceFacts> interfaces = {{"lo", "127.0.0.1", true, true, false},
                                                         {"eth0", "192.168.10.3", true, false, true}};
  HostNeeds needs;
  needs.dds.push_back({"follower", "follower.yaml", {"192.168.10.3"}, true});
  auto findings = check_dds(interfaces, needs);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].verdict, Verdict::kOk);
  EXPECT_NE(findings[0].found.find("eth0 192.168.10.3 (multicast)"), std::string::npos);
  needs.dds[0].interface_whitelist = {"192.168.10.4"};
  findings = check_dds(interfaces, needs);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[1].verdict, Verdict::kFail);
  EXPECT_NE(findings[1].found.find("192.168.10.4"), std::string::npos);
}

TEST(DoctorDds, LoopbackAloneOrNoMulticastForMulticastDiscoveryWarns) {
  HostNeeds needs;
  needs.dds.push_back({"leader", "leader.yaml", {}, true});
  EXPECT_EQ(check_dds({{"lo", "127.0.0.1", true, true, false}}, needs)[0].verdict, Verdict::kWarn);
  const std::vector<NetworkInterfaceFacts> no_multicast = {{"wg0", "10.0.0.2", true, false, false}};
  EXPECT_EQ(check_dds(no_multicast, needs)[0].verdict, Verdict::kWarn);
  needs.dds[0].multicast_discovery = false;
  EXPECT_EQ(check_dds(no_multicast, needs)[0].verdict, Verdict::kOk) << "discovery: peers needs no multicast";
}

TEST(DoctorProvisioning, NamesEachMissingFileAndTheGroup) {
  ProvisioningFacts p;
  p.user = "operator";
  const Finding none = check_provisioning(p);
  EXPECT_EQ(none.verdict, Verdict::kWarn);
  for (const char* file : {"95-teleop.conf", "60-teleop.rules", "teleop-node@.service", "group teleop"}) {
    EXPECT_NE(none.found.find(file), std::string::npos) << file;
  }
  p.limits_file = p.udev_rules = p.node_unit = p.group_exists = true;
  EXPECT_EQ(check_provisioning(p).verdict, Verdict::kWarn) << "operator is not in the group";
  p.in_group = true;
  EXPECT_EQ(check_provisioning(p).verdict, Verdict::kOk);
}

TEST(DoctorFindings, AFailMakesTheExitCodeOneAndEveryMissPrintsItsFix) {
  std::vector<Finding> findings = {{"kernel", Verdict::kWarn, "stock", "install rt"}, {"clock", Verdict::kOk, "synced", ""}};
  EXPECT_EQ(exit_code(findings), 0);
  findings.push_back({"can0", Verdict::kFail, "missing", "plug it in"});
  EXPECT_EQ(exit_code(findings), 1);
  const std::string text = findings_text(findings);
  EXPECT_NE(text.find("  warn  kernel  stock\n"), std::string::npos) << text;
  EXPECT_NE(text.find("fix: install rt\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  FAIL  can0    missing\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace teleop::doctor
