#include "teleop/transport/callback_gate.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace teleop::transport {
namespace {

TEST(CallbackGate, CloseWaitsForARunningCallbackAndNoneRunsAfter) {
  CallbackGate gate;
  std::atomic<bool> started{false};
  std::atomic<bool> finished{false};
  std::atomic<int> calls{0};
  const auto guarded = gate.guard(std::function<void(int)>([&](int) {
    ++calls;
    started = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    finished = true;
  }));
  // a Fast DDS thread in the callback while its owner goes
  std::thread dds([&] { guarded(1); });
  while (!started) std::this_thread::yield();
  gate.close();
  EXPECT_TRUE(finished) << "close() returned while the callback still ran";
  dds.join();
  guarded(2);
  EXPECT_EQ(calls, 1) << "a callback ran after close()";
}

TEST(CallbackGate, AGuardedCallbackOutlivingItsGateDoesNothing) {
  int calls = 0;
  std::function<void(int)> guarded;
  {
    CallbackGate gate;
    guarded = gate.guard(std::function<void(int)>([&](int) { ++calls; }));
    guarded(1);
  }
  guarded(2);
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace teleop::transport
