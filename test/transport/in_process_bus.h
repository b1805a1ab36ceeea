#pragma once
// Participants of one test process meeting each other: a domain and topic names of this process
// only (concurrent test runs never match each other's endpoints), shared memory so that they find
// each other where UDP multicast is unavailable, and a bounded wait for what DDS does on its own
// threads. participant_test.cpp has its own, for its helper processes.

#include <unistd.h>

#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <thread>

#include "teleop/transport/participant_config.h"
#include "teleop/transport/topics.h"

namespace teleop::transport::test_bus {

inline int domain() { return static_cast<int>(getpid() % 100) + 100; }

inline std::string topic_name(const std::string& leaf) {
  return "teleop_test/" + std::to_string(getpid()) + "/" + leaf;
}

/// A stream topic of JointState named after `leaf` (the spec points at storage that lives on).
inline TopicSpec<msg::JointState> stream_topic(const std::string& leaf) {
  static std::map<std::string, std::string> names;
  std::string& name = names[leaf];
  if (name.empty()) name = topic_name(leaf);
  return {name.c_str(), QosPreset::kStream};
}

inline ParticipantConfig config(const std::string& name) {
  ParticipantConfig c;
  c.domain_id = domain();
  c.name = name;
  c.shm = true;
  return c;
}

/// Polls `done` every millisecond for up to 5 s (a bound on a hang, not a measurement).
inline bool wait_for(const std::function<bool()>& done) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return done();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace teleop::transport::test_bus
