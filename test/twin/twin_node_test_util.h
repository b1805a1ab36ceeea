#pragma once
// Driving the twin node in a test: what a peer publishes, then one cycle, many times.

#include <chrono>
#include <cstdint>
#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::twin::test {

/// `cycles` times: `publish(i)`, a pause for the delivery, one cycle of `node`. Returns the
/// allocations the cycles made (the publishing and the pause not counted).
template <typename Publish>
uint64_t drive_cycles(runtime::NodeLogic& node, teleop::test::NodeHarness& harness, int cycles, Publish&& publish) {
  uint64_t allocations = 0;
  for (int i = 0; i < cycles; ++i) {
    publish(i);
    std::this_thread::sleep_for(std::chrono::microseconds(300));
    const CycleTick tick = harness.tick();
    teleop::test::ScopedAllocationCounter counter;
    node.cycle(tick);
    allocations += counter.count();
  }
  return allocations;
}

}  // namespace teleop::twin::test
