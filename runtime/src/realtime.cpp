#include "teleop/runtime/realtime.h"

#include <dirent.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

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

namespace {

// the thread's name, as the kernel keeps it
std::string name_of(pid_t tid) {
  char path[64];
  std::snprintf(path, sizeof(path), "/proc/self/task/%d/comm", static_cast<int>(tid));
  FILE* f = std::fopen(path, "r");
  if (f == nullptr) return {};
  char name[32] = {};
  const bool read = std::fgets(name, sizeof(name), f) != nullptr;
  std::fclose(f);
  std::string n = read ? name : "";
  if (!n.empty() && n.back() == '\n') n.pop_back();
  return n;
}

}  // namespace

void name_own_thread(const char* what) {
  char name[16];
  std::snprintf(name, sizeof(name), "teleop-%s", what);
  pthread_setname_np(pthread_self(), name);
}

ThreadCensus place_other_threads(const RealtimeConfig& config) {
  ThreadCensus census;
  const pid_t self = gettid();
  DIR* tasks = opendir("/proc/self/task");
  if (tasks == nullptr) return census;
  while (const dirent* entry = readdir(tasks)) {
    const pid_t tid = static_cast<pid_t>(std::atoi(entry->d_name));
    if (tid <= 0 || tid == self) continue;
    const bool own = name_of(tid).rfind("teleop-", 0) == 0;
    sched_param param{};
    int policy = SCHED_OTHER;
    if (!own && config.dds_priority > 0) {
      policy = SCHED_FIFO;
      param.sched_priority = config.dds_priority;
    }
    if (sched_setscheduler(tid, policy, &param) != 0) {
      ++census.refused;
    } else {
      ++(own ? census.own : census.middleware);
    }
  }
  closedir(tasks);
  return census;
}

}  // namespace teleop::runtime
