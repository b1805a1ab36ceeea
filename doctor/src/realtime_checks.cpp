// The checks of what a 1 kHz loop needs of the kernel and the scheduler (checks.h).
#include <algorithm>
#include <string>

#include "teleop/doctor/checks.h"

namespace teleop::doctor {
namespace {

// the verdict of a miss: a node with `realtime: required` stops at start, anything else runs
Verdict miss(const HostNeeds& needs) { return needs.realtime_required() ? Verdict::kFail : Verdict::kWarn; }

std::string limit_text(uint64_t value, const char* unit) {
  if (value == kUnlimited) return "unlimited";
  return std::to_string(value) + unit;
}

std::string who_asks(const HostNeeds& needs) {
  std::string nodes;
  for (const RealtimeNeed& r : needs.realtime) {
    if (r.realtime.mode == runtime::RealtimeMode::kOff) continue;
    nodes += (nodes.empty() ? "" : ", ") + r.node +
             (r.realtime.mode == runtime::RealtimeMode::kRequired ? " (required)" : " (optional)");
  }
  return nodes.empty() ? "no config asks for it" : "asked by " + nodes;
}

const char* const kLimitsFix =
    "the .deb's /etc/security/limits.d/95-teleop.conf gives the group teleop rtprio 95 and unlimited memlock: "
    "sudo usermod -aG teleop $USER, then log in again (a service: teleop-node@.service sets its own limits; "
    "docs/provisioning.md)";

}  // namespace

Finding check_kernel(const KernelFacts& kernel) {
  if (kernel.realtime_flag || kernel.version.find("PREEMPT_RT") != std::string::npos) {
    return {"kernel", Verdict::kOk, "PREEMPT_RT " + kernel.release, ""};
  }
  std::string preemption = kernel.version.find("PREEMPT_DYNAMIC") != std::string::npos ? "PREEMPT_DYNAMIC"
                           : kernel.version.find("PREEMPT") != std::string::npos       ? "PREEMPT"
                                                                                      : "no preemption";
  if (!kernel.preemption.empty()) preemption += ", " + kernel.preemption;
  return {"kernel", Verdict::kWarn,
          kernel.release + " is not PREEMPT_RT (" + preemption +
              "): the loop's lateness tail reaches milliseconds under load",
          "sudo apt install linux-image-rt-amd64 and boot it"};
}

Finding check_rtprio(const SchedulingFacts& scheduling, const HostNeeds& needs) {
  const int priority = needs.judged_priority();
  const std::string asked = "SCHED_FIFO " + std::to_string(priority) + " (" + who_asks(needs) + ")";
  // a trial on a thread is the truth; without one, the limit and the capability say it
  bool allowed = scheduling.cap_sys_nice || scheduling.rtprio_soft >= static_cast<uint64_t>(priority);
  std::string found = asked + ": rtprio limit " + limit_text(scheduling.rtprio_soft, "") +
                      (scheduling.cap_sys_nice ? ", CAP_SYS_NICE" : "");
  if (scheduling.fifo_trial && scheduling.fifo_trial_priority == priority) {
    allowed = scheduling.fifo_trial->empty();
    found += allowed ? ", a thread got it" : ", refused to a thread: " + *scheduling.fifo_trial;
  }
  if (allowed) return {"rtprio", Verdict::kOk, found, ""};
  return {"rtprio", miss(needs), found, kLimitsFix};
}

Finding check_memlock(const SchedulingFacts& scheduling, const HostNeeds& needs) {
  // mlockall(MCL_CURRENT | MCL_FUTURE) locks all a node maps (MuJoCo, Fast DDS's pools: hundreds
  // of MiB), and after it every allocation beyond the limit fails
  constexpr uint64_t kEnough = uint64_t{1} << 30;
  const std::string found = "memlock limit " + limit_text(scheduling.memlock_soft, " bytes") +
                            (scheduling.cap_ipc_lock ? ", CAP_IPC_LOCK" : "");
  if (scheduling.cap_ipc_lock || scheduling.memlock_soft == kUnlimited) return {"memlock", Verdict::kOk, found, ""};
  if (scheduling.memlock_soft >= kEnough) {
    return {"memlock", Verdict::kWarn, found + ": a node that maps more fails its allocations after mlockall",
            kLimitsFix};
  }
  return {"memlock", miss(needs), found + ": below the 1 GiB a node locks (" + who_asks(needs) + ")", kLimitsFix};
}

Finding check_rt_throttling(const SchedulingFacts& scheduling) {
  const std::string found = "sched_rt_runtime_us " + std::to_string(scheduling.rt_runtime_us) + " of " +
                            std::to_string(scheduling.rt_period_us);
  // the kernel's default keeps 5 % for everything else; much less real-time time stalls the loop
  if (scheduling.rt_runtime_us < 0 || scheduling.rt_runtime_us * 10 >= scheduling.rt_period_us * 9) {
    return {"rt throttling", Verdict::kOk, found, ""};
  }
  return {"rt throttling", Verdict::kWarn, found + ": real-time threads are stopped for the rest of each period",
          "echo 950000 | sudo tee /proc/sys/kernel/sched_rt_runtime_us"};
}

Finding check_governors(const CpuFacts& cpu) {
  if (cpu.governors.empty()) return {"cpu governor", Verdict::kOk, "no cpufreq (a fixed clock, or a VM)", ""};
  const auto slow = std::count_if(cpu.governors.begin(), cpu.governors.end(),
                                  [](const std::string& g) { return g != "performance"; });
  const std::string of = " of " + std::to_string(cpu.governors.size()) + " CPUs";
  if (slow == 0) return {"cpu governor", Verdict::kOk, "performance on all" + of, ""};
  const auto first = std::find_if(cpu.governors.begin(), cpu.governors.end(),
                                  [](const std::string& g) { return g != "performance"; });
  return {"cpu governor", Verdict::kWarn,
          *first + " on " + std::to_string(slow) + of + ": the clock ramps up only after the loop is late",
          "sudo cpupower frequency-set -g performance (package linux-cpupower)"};
}

Finding check_clock(const ClockFacts& clock) {
  std::string daemons;
  for (const std::string& d : clock.daemons) daemons += (daemons.empty() ? "" : ", ") + d;
  const std::string by = daemons.empty() ? "no time daemon running" : daemons;
  if (clock.synchronised) {
    return {"clock", Verdict::kOk,
            "synchronised (" + by + "), max error " + std::to_string(clock.max_error_us / 1000) + " ms", ""};
  }
  return {"clock", Verdict::kWarn,
          "not synchronised (" + by +
              "): the nodes estimate each peer's offset, but latencies across hosts mean nothing",
          "sudo apt install chrony, or ptp4l + phc2sys on a PTP network (docs/clocks.md)"};
}

}  // namespace teleop::doctor
