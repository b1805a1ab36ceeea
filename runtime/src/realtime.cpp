#include "teleop/runtime/realtime.h"

#include <dirent.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace teleop::runtime {

std::string apply_realtime(const RealtimeConfig& config) {
  if (config.mode == RealtimeMode::kOff) return {};
  // no page faults in the loop: lock what is mapped now and what will be
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    return std::string("mlockall failed: ") + std::strerror(errno);
  }
  sched_param param{};
  param.sched_priority = config.priority;
  if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); err != 0) {
    return "SCHED_FIFO priority " + std::to_string(config.priority) + " refused: " + std::strerror(err) +
           " (needs CAP_SYS_NICE or an rtprio limit)";
  }
  return {};
}

ThreadCensus keep_other_threads_below() {
  ThreadCensus census;
  const pid_t self = gettid();
  DIR* tasks = opendir("/proc/self/task");
  if (tasks == nullptr) return census;
  while (const dirent* entry = readdir(tasks)) {
    const pid_t tid = static_cast<pid_t>(std::atoi(entry->d_name));
    if (tid <= 0 || tid == self) continue;
    ++census.threads;
    const int policy = sched_getscheduler(tid);
    if (policy != SCHED_FIFO && policy != SCHED_RR) continue;
    ++census.realtime;
    sched_param normal{};
    if (sched_setscheduler(tid, SCHED_OTHER, &normal) == 0) ++census.demoted;
  }
  closedir(tasks);
  return census;
}

}  // namespace teleop::runtime
