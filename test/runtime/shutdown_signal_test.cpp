#include "teleop/runtime/shutdown_signal.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

#include "teleop/common/clock.h"

namespace teleop::runtime {
namespace {

// The flag is process-wide and never cleared, so every test holds whatever ran before it.

TEST(ShutdownSignal, SetsFlagAndTimeWhenSigtermArrivesAfterInstall) {
  install_shutdown_handlers();
  install_shutdown_handlers();  // idempotent
  // without the handler the default action would end this test process
  ASSERT_EQ(std::raise(SIGTERM), 0);
  EXPECT_TRUE(shutdown_requested());
  EXPECT_GT(shutdown_requested_at_ns(), 0);
  EXPECT_LE(shutdown_requested_at_ns(), monotonic_now_ns());
}

TEST(ShutdownSignal, SetsFlagWhenSigintArrivesAfterInstall) {
  install_shutdown_handlers();
  ASSERT_EQ(std::raise(SIGINT), 0);
  EXPECT_TRUE(shutdown_requested());
  EXPECT_GT(shutdown_requested_at_ns(), 0);
}

TEST(ShutdownSignal, SetsFlagWhenRequestedFromInside) {
  request_shutdown();
  EXPECT_TRUE(shutdown_requested());
  EXPECT_GT(shutdown_requested_at_ns(), 0);
  EXPECT_LE(shutdown_requested_at_ns(), monotonic_now_ns());
}

TEST(ShutdownSignal, KeepsTimeOfFirstRequestWhenRequestedAgain) {
  request_shutdown();
  const int64_t first = shutdown_requested_at_ns();
  ASSERT_GT(first, 0);
  request_shutdown();
  install_shutdown_handlers();
  ASSERT_EQ(std::raise(SIGTERM), 0);
  EXPECT_EQ(shutdown_requested_at_ns(), first);
  EXPECT_TRUE(shutdown_requested());
}

// before a node joins the network nothing polls the flag: the signal ends the process itself
TEST(ShutdownSignalDeathTest, ExitsAtOnceWith128PlusTheSignalWhileSwitchedOn) {
  for (const int sig : {SIGTERM, SIGINT}) {
    EXPECT_EXIT(
        {
          set_signals_exit_at_once(true);
          install_shutdown_handlers();
          std::raise(sig);
          std::abort();  // not reached
        },
        ::testing::ExitedWithCode(128 + sig), "stopped by a signal before joining the network");
  }
}

TEST(ShutdownSignalDeathTest, SetsTheFlagAgainOnceSwitchedOff) {
  EXPECT_EXIT(
      {
        set_signals_exit_at_once(true);
        install_shutdown_handlers();
        set_signals_exit_at_once(false);
        std::raise(SIGTERM);
        std::exit(shutdown_requested() ? 7 : 8);
      },
      ::testing::ExitedWithCode(7), "");
}

}  // namespace
}  // namespace teleop::runtime
