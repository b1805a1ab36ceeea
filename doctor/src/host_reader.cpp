// The facts the kernel gives this process: limits, capabilities, a SCHED_FIFO trial, adjtimex,
// the network interfaces; and read_host(), which gathers everything (host_reader.h).
#include "teleop/doctor/host_reader.h"

#include <ifaddrs.h>
#include <arpa/inet.h>
#include <net/if.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/timex.h>

#include <cstring>
#include <fstream>
#include <thread>

namespace teleop::doctor {
namespace {

uint64_t soft_limit(int resource) {
  rlimit limit{};
  if (::getrlimit(resource, &limit) != 0) return 0;
  return limit.rlim_cur == RLIM_INFINITY ? kUnlimited : static_cast<uint64_t>(limit.rlim_cur);
}

// this process's effective capabilities (/proc/self/status CapEff, a hex mask)
uint64_t effective_capabilities() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("CapEff:", 0) == 0) return std::stoull(line.substr(7), nullptr, 16);
  }
  return 0;
}

int64_t read_number(const std::string& file, int64_t fallback) {
  std::ifstream in(file);
  int64_t value = fallback;
  in >> value;
  return in ? value : fallback;
}

// what SCHED_FIFO at `priority` answers on a thread that ends right after: the truth about
// limits, capabilities and cgroups together, without changing this process
std::string fifo_trial(int priority) {
  std::string answer;
  std::thread probe([&] {
    sched_param param{};
    param.sched_priority = priority;
    if (const int err = ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &param); err != 0) {
      answer = std::strerror(err);
    }
  });
  probe.join();
  return answer;
}

SchedulingFacts read_scheduling(const HostNeeds& needs, const std::string& root) {
  constexpr int kCapIpcLock = 14;
  constexpr int kCapSysNice = 23;
  SchedulingFacts s;
  s.rtprio_soft = soft_limit(RLIMIT_RTPRIO);
  s.memlock_soft = soft_limit(RLIMIT_MEMLOCK);
  const uint64_t caps = effective_capabilities();
  s.cap_sys_nice = (caps >> kCapSysNice) & 1u;
  s.cap_ipc_lock = (caps >> kCapIpcLock) & 1u;
  s.fifo_trial_priority = needs.judged_priority();
  s.fifo_trial = fifo_trial(s.fifo_trial_priority);
  s.rt_runtime_us = read_number(root + "/proc/sys/kernel/sched_rt_runtime_us", s.rt_runtime_us);
  s.rt_period_us = read_number(root + "/proc/sys/kernel/sched_rt_period_us", s.rt_period_us);
  return s;
}

ClockFacts read_clock(const std::string& root) {
  ClockFacts c;
  timex tx{};
  const int state = ::adjtimex(&tx);
  c.synchronised = state != -1 && state != TIME_ERROR && (tx.status & STA_UNSYNC) == 0;
  c.max_error_us = tx.maxerror;
  c.estimated_error_us = tx.esterror;
  c.daemons = read_time_daemons(root);
  return c;
}

std::vector<NetworkInterfaceFacts> read_interfaces() {
  std::vector<NetworkInterfaceFacts> found;
  ifaddrs* all = nullptr;
  if (::getifaddrs(&all) != 0) return found;
  for (const ifaddrs* a = all; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_INET) continue;
    char address[INET_ADDRSTRLEN] = {};
    ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(a->ifa_addr)->sin_addr, address, sizeof(address));
    found.push_back({a->ifa_name, address, (a->ifa_flags & IFF_UP) != 0, (a->ifa_flags & IFF_LOOPBACK) != 0,
                     (a->ifa_flags & IFF_MULTICAST) != 0});
  }
  ::freeifaddrs(all);
  return found;
}

}  // namespace

HostFacts read_host(const HostNeeds& needs, const std::string& root) {
  HostFacts facts;
  facts.kernel = read_kernel(root);
  facts.scheduling = read_scheduling(needs, root);
  facts.cpu.governors = read_governors(root);
  facts.clock = read_clock(root);
  for (const CanNeed& need : needs.can) facts.can_links.push_back(read_can_link(need.interface));
  facts.input_devices = read_input_devices(root);
  facts.interfaces = read_interfaces();
  facts.provisioning = read_provisioning(root);
  return facts;
}

}  // namespace teleop::doctor
