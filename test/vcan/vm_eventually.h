#pragma once
// Waiting in the VM's tests for what another thread or process does: a condition polled every
// 10 ms until it holds or the time is up (the VM runs at a fraction of real time).

#include <chrono>
#include <functional>
#include <thread>

namespace teleop::test {

inline bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds within) {
  const auto until = std::chrono::steady_clock::now() + within;
  while (std::chrono::steady_clock::now() < until) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return condition();
}

}  // namespace teleop::test
