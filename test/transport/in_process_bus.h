#pragma once
// Participants of one test process meeting each other: a domain and topic names of this process
// only (concurrent test runs never match each other's endpoints), shared memory so that they find
// each other where UDP multicast is unavailable, and a bounded wait for what DDS does on its own
// threads. participant_test.cpp has its own, for its helper processes.

#include <unistd.h>

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "teleop/transport/discovery_observer.h"
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

/// What discovery reports of the writers on the bus: the last one heard of per topic.
class DiscoveredWriters : public DiscoveryObserver {
 public:
  void on_participant(const ParticipantInfo&, bool) override {}
  void on_endpoint(const EndpointInfo& e, bool present) override {
    std::lock_guard lock(mutex_);
    if (e.is_writer && present) writers_[e.topic] = e;
  }
  std::map<std::string, EndpointInfo> by_topic() {
    std::lock_guard lock(mutex_);
    return writers_;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, EndpointInfo> writers_;
};

}  // namespace teleop::transport::test_bus
