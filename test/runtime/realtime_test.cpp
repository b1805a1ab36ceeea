// The middleware's threads run below the node's loop and above ordinary processes; the node's own
// helpers stay ordinary. Needs CAP_SYS_NICE to set SCHED_FIFO (CI runs as root, as the netns
// tests do); without it the test fails and says so, never skips.
#include "teleop/runtime/realtime.h"

#include <gtest/gtest.h>
#include <sched.h>

#include <atomic>
#include <thread>

namespace teleop::runtime {
namespace {

// a thread that reports the kernel's word on its own policy and priority until stopped
struct Watched {
  std::atomic<bool> stop{false};
  std::atomic<int> policy{-1};
  std::atomic<int> priority{-1};
  std::thread thread;

  explicit Watched(const char* own_name) {
    thread = std::thread([this, own_name] {
      if (own_name != nullptr) name_own_thread(own_name);
      while (!stop.load()) {
        sched_param p{};
        sched_getparam(0, &p);
        priority.store(p.sched_priority);
        // glibc's pthread_getschedparam would return what pthread_setschedparam cached
        policy.store(sched_getscheduler(0));
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
    while (policy.load() < 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~Watched() {
    stop.store(true);
    thread.join();
  }
  void wait_for(int expected_policy) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (policy.load() != expected_policy && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
};

TEST(Realtime, PutsTheMiddlewareBelowTheLoopAndTheNodesOwnHelpersAmongOrdinaryProcesses) {
  Watched middleware(nullptr);  // Fast DDS names none of its threads
  Watched helper("log");
  RealtimeConfig config;
  config.priority = 80;
  config.dds_priority = 70;
  const ThreadCensus census = place_other_threads(config);
  ASSERT_EQ(census.refused, 0) << "setting SCHED_FIFO needs CAP_SYS_NICE (run as root)";
  EXPECT_GE(census.middleware, 1);
  EXPECT_EQ(census.own, 1);
  middleware.wait_for(SCHED_FIFO);
  EXPECT_EQ(middleware.policy.load(), SCHED_FIFO);
  EXPECT_EQ(middleware.priority.load(), 70);
  EXPECT_EQ(helper.policy.load(), SCHED_OTHER);
  // dds_priority 0: the middleware among ordinary processes too
  config.dds_priority = 0;
  (void)place_other_threads(config);
  middleware.wait_for(SCHED_OTHER);
  EXPECT_EQ(middleware.policy.load(), SCHED_OTHER);
}

}  // namespace
}  // namespace teleop::runtime
