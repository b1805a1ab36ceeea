#pragma once
// Nodes say what they wait for: a subscribed topic that has had no writer for a few seconds is
// logged once ("waiting for a writer on teleop/leader/joint_command, domain 60"), and again when a
// writer appears. NodeStatus carries the same (FlowStatus.writers), for `teleop monitor`.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "stop_request.h"
#include "teleop/transport/participant.h"

namespace teleop::runtime {

struct FlowEvent {
  enum class Kind { kWaiting, kAppeared };
  Kind kind;
  size_t flow;
  /// How long the flow had had no writer [s].
  double without_writer_s;
};

/// Which flows to report, from their writer counts over time. Pure logic: no clock, no thread.
class FlowWaitTracker {
 public:
  FlowWaitTracker(size_t flows, int64_t grace_ns, int64_t start_ns);
  /// `writers[i]`: writers matched now on flow i. Appends what is to be reported.
  void update(int64_t now_ns, const std::vector<int32_t>& writers, std::vector<FlowEvent>& events);

 private:
  struct Flow {
    bool has_writer;
    int64_t without_since_ns;  // when it last had one (or the start)
    bool reported = false;
  };
  std::vector<Flow> flows_;
  int64_t grace_ns_;
};

/// Watches a participant's readers from a thread of its own (never the control loop's) and logs
/// the events.
class FlowWatch {
 public:
  FlowWatch(const transport::Participant& participant, std::string node_name, int domain_id,
            int64_t grace_ns = 3'000'000'000);
  ~FlowWatch();
  FlowWatch(const FlowWatch&) = delete;
  FlowWatch& operator=(const FlowWatch&) = delete;

 private:
  void run();
  void log(const FlowEvent& event) const;

  std::vector<transport::ReaderFlow> flows_;
  std::string node_name_;
  int domain_id_;
  FlowWaitTracker tracker_;
  StopRequest stop_;
  std::thread thread_;
};

}  // namespace teleop::runtime
