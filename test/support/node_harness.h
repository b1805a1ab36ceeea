#pragma once
// Runs a node's logic in a test: a real participant (UDP only, a domain of its own) plus a peer
// participant standing in for the other nodes, and cycles driven by the test.

#include <unistd.h>

#include <chrono>
#include <functional>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/participant.h"

namespace teleop::test {

inline transport::ParticipantConfig test_participant_config(const std::string& name) {
  transport::ParticipantConfig c;
  // each test executable runs as its own process under ctest: the pid picks a free domain
  c.domain_id = 150 + static_cast<int>(getpid() % 80);
  c.name = name;
  c.udpv4 = true;
  c.shm = false;
  c.interface_whitelist = {"127.0.0.1"};
  c.liveliness_lease_ns = 1'000'000'000;
  return c;
}

/// Polls `condition` every millisecond for up to `timeout`.
inline bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

/// The node under test and a peer for the other side of its topics.
struct NodeHarness {
  runtime::NodeConfig node_config;
  transport::Participant node_participant{test_participant_config("under_test")};
  transport::Participant peer{test_participant_config("peer")};
  runtime::NodeContext context{node_config, node_participant};
  uint64_t index = 0;

  explicit NodeHarness(const std::string& name) { node_config.name = name; }

  /// A tick at the current monotonic time.
  CycleTick tick() {
    const int64_t now = monotonic_now_ns();
    return CycleTick{index++, now, now};
  }
};

}  // namespace teleop::test
