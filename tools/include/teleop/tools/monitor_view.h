#pragma once
// What `teleop monitor` shows of every node on the bus, from the NodeStatus samples it receives:
// state, faults by name, measured loop rate, overruns, lateness, each subscribed flow (writers,
// newest-sample age, latency, loss, whom it follows and what it refuses) and each impaired link,
// TDPA energy, CAN bus state; two nodes with one name are shown as such, not merged. Pure: the
// monitor feeds it samples and times.

#include <array>
#include <cstdint>
#include <map>
#include <string>

#include <teleop/msg/status.h>

#include "teleop/common/stream_session.h"

namespace teleop::tools {

class MonitorView {
 public:
  /// A node is shown as silent once its newest status is older than this.
  explicit MonitorView(int64_t silent_after_ns = 2'000'000'000) : silent_after_ns_(silent_after_ns) {}

  /// A status received at `now_ns` (the monitor's CLOCK_MONOTONIC) from the status writer `writer`.
  void update(const msg::NodeStatus& status, int64_t now_ns, const WriterId& writer = {});

  /// The terminal screen: a header line, a row per node, an indented row per flow and link.
  std::string table(int64_t now_ns, int domain_id) const;
  /// One line per node (for logs and pipes).
  std::string lines(int64_t now_ns) const;
  size_t nodes() const { return nodes_.size(); }

 private:
  struct Node {
    msg::NodeStatus last;
    msg::NodeStatus previous;
    bool seen = false;
    bool has_previous = false;
    int64_t received_ns = 0;
    /// Status writers heard under this name, and when last. Statuses that come back to a writer
    /// heard before (not a restarted node, whose new writer simply replaces the old) are a clash
    /// of two nodes with one name, shown until `clash_until_ns`.
    std::map<std::array<uint8_t, 16>, int64_t> writers;
    std::array<uint8_t, 16> last_writer{};
    int64_t clash_until_ns = 0;
  };
  std::string state_text(const Node& node, int64_t now_ns) const;
  /// Writers of this name heard within the silence bound.
  size_t live_writers(const Node& node, int64_t now_ns) const;

  std::map<std::string, Node> nodes_;
  int64_t silent_after_ns_;
};

}  // namespace teleop::tools
