#include "node_event_log.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <mutex>

#include "teleop/common/version.h"
#include "teleop/runtime/command_authority.h"
#include "teleop/runtime/realtime.h"
#include "teleop/runtime/status_names.h"

namespace teleop::runtime {

StateWatch::StateWatch(NodeEventQueue& queue) : queue_(queue) { faults_.reserve(msg::MAX_FAULTS); }

uint32_t StateWatch::fault_mask(const NodeLogic& logic) {
  faults_.clear();
  logic.active_faults(faults_);
  uint32_t mask = 0;
  for (const uint32_t f : faults_) mask |= f < 32 ? uint32_t{1} << f : 0u;
  return mask;
}

bool StateWatch::after_cycle(const CycleTick& tick, const NodeLogic& logic, const PacerStats& loop) {
  if (loop.skipped > skipped_ && !first_) {
    NodeEvent e;
    e.kind = NodeEvent::Kind::kStall;
    e.mono_ns = tick.now_ns;
    e.count = loop.skipped - skipped_;
    e.value = static_cast<double>(tick.deadline_ns - last_deadline_ns_) * 1e-9;
    queue_.push(e);
  }
  skipped_ = loop.skipped;
  last_deadline_ns_ = tick.deadline_ns;
  const msg::NodeState state = logic.state();
  const uint32_t mask = fault_mask(logic);
  if (!first_ && state == state_ && mask == mask_) return false;
  NodeEvent e;
  e.kind = NodeEvent::Kind::kState;
  e.mono_ns = tick.now_ns;
  e.code = static_cast<int32_t>(state);
  e.previous = first_ ? -1 : static_cast<int32_t>(state_);
  e.faults = mask;
  queue_.push(e);
  first_ = false;
  state_ = state;
  mask_ = mask;
  return true;
}

namespace {

std::string fault_list(uint32_t mask) {
  std::string out;
  for (uint32_t f = 1; f < 32; ++f) {
    if ((mask & (uint32_t{1} << f)) == 0) continue;
    if (!out.empty()) out += ", ";
    out += fault_name(f);
  }
  return out;
}

std::string state_line(const NodeEvent& e, const std::string& node) {
  const auto state = static_cast<msg::NodeState>(e.code);
  std::string line = node + ": ";
  line += e.previous < 0 ? std::string(state_name(state))
                         : std::string(state_name(static_cast<msg::NodeState>(e.previous))) + " -> " + state_name(state);
  const std::string faults = fault_list(e.faults);
  if (!faults.empty()) line += " (" + faults + ")";
  return line;
}

std::string refusal_line(const NodeEvent& e, const std::string& node) {
  std::string line = node + ": " + std::string(e.topic.view()) + " refuses samples of '" + std::string(e.who.view()) + "': ";
  switch (static_cast<uint32_t>(e.code)) {
    case msg::REFUSAL_OTHER_WRITER: line += "another writer is followed ('" + std::string(e.detail.view()) + "')"; break;
    case msg::REFUSAL_NOT_ACCEPTED: line += "its node is not one this node accepts"; break;
    case msg::REFUSAL_SEQUENCE_JUMP: line += "its sequence number leapt beyond the bound"; break;
    case msg::REFUSAL_INVALID: line += "invalid (" + std::string(e.detail.view()) + ")"; break;
    default: line += refusal_name(static_cast<uint32_t>(e.code)); break;
  }
  return line + "; further ones are counted in its status";
}

std::string authority_line(const NodeEvent& e, const std::string& node) {
  const auto refusal = static_cast<CommandRefusal>(e.code);
  if (refusal == CommandRefusal::kNone) return node + ": in command (its commands are in force)";
  std::string line = node + ": not in command: " + to_string(refusal);
  if (!e.who.empty()) line += " at '" + std::string(e.who.view()) + "'";
  if (!e.detail.empty()) line += " (" + std::string(e.detail.view()) + ")";
  return line;
}

std::string version_line(const NodeEvent& e, const std::string& node) {
  if (e.code == 0) return node + ": the node of another version is gone; `teleop enable` resumes";
  return fmt::format(
      "{}: STOPPED, VERSION MISMATCH: '{}' speaks protocol {}, messages {} (teleop {}); this node protocol {}, "
      "messages {} (teleop {}): their samples would decode as garbage. Run one release on every host",
      node, e.who.view(), e.count, e.topic.view(), e.detail.view(), kProtocolVersion, message_version(),
      software_version());
}

std::string architecture_line(const NodeEvent& e, const std::string& node) {
  if (e.code == 0) return node + ": the node of another architecture is gone; `teleop enable` resumes";
  return fmt::format(
      "{}: STOPPED, ARCHITECTURE MISMATCH: '{}' plays {}, this node plays {}: their samples would mean "
      "different things on the two sides (docs/architectures.md). Give every node of the pair one "
      "teleoperation.architecture",
      node, e.who.view(), e.detail.view(), e.topic.view());
}

}  // namespace

std::string format_event(const NodeEvent& e, const std::string& node) {
  switch (e.kind) {
    case NodeEvent::Kind::kState: return state_line(e, node);
    case NodeEvent::Kind::kFollowing:
      return node + ": " + std::string(e.topic.view()) + " follows '" + std::string(e.who.view()) + "' (session " +
             std::to_string(e.count) + ")";
    case NodeEvent::Kind::kRefused: return refusal_line(e, node);
    case NodeEvent::Kind::kStall:
      return fmt::format("{}: the loop stalled for {:.3f} s ({} deadlines skipped)", node, e.value, e.count);
    case NodeEvent::Kind::kAuthority: return authority_line(e, node);
    case NodeEvent::Kind::kVersionMismatch: return version_line(e, node);
    case NodeEvent::Kind::kArchitectureMismatch: return architecture_line(e, node);
    case NodeEvent::Kind::kClockOffset:
      return fmt::format(
          "{}: the clock of '{}' reads {:.1f} ms {} ours (its fastest samples on {} arrive {:.1f} ms after their "
          "stamps): command ages are judged beyond its fastest sample; synchronise the hosts' clocks for "
          "latencies that mean something (docs/clocks.md)",
          node, e.who.view(), std::abs(e.value) * 1e3, e.value < 0 ? "ahead of" : "behind", e.topic.view(), e.value * 1e3);
    case NodeEvent::Kind::kEmergencyStop:
      return node +
             (e.code == 1   ? ": EMERGENCY STOP from '"
              : e.code == 2 ? ": enabled after its hold by '"
                            : ": enabled after the emergency stop by '") +
             std::string(e.who.view()) + "' (" + std::string(e.topic.view()) + ")" +
             (e.code == 1 ? "; only `teleop enable` resumes" : "");
  }
  return node + ": unknown event";
}

namespace {

spdlog::level::level_enum level_of(const NodeEvent& e) {
  switch (e.kind) {
    case NodeEvent::Kind::kState: {
      const auto s = static_cast<msg::NodeState>(e.code);
      return s == msg::STATE_SAFE_HOLD || s == msg::STATE_FAULT ? spdlog::level::warn : spdlog::level::info;
    }
    case NodeEvent::Kind::kFollowing: return spdlog::level::info;
    case NodeEvent::Kind::kAuthority:
      return static_cast<CommandRefusal>(e.code) == CommandRefusal::kNone ? spdlog::level::info : spdlog::level::warn;
    case NodeEvent::Kind::kRefused:
    case NodeEvent::Kind::kStall: return spdlog::level::warn;
    case NodeEvent::Kind::kEmergencyStop: return e.code == 1 ? spdlog::level::err : spdlog::level::warn;
    case NodeEvent::Kind::kClockOffset: return spdlog::level::warn;
    case NodeEvent::Kind::kVersionMismatch:
    case NodeEvent::Kind::kArchitectureMismatch: return e.code != 0 ? spdlog::level::err : spdlog::level::warn;
  }
  return spdlog::level::info;
}

}  // namespace

NodeEventLog::NodeEventLog(NodeEventQueue& queue, std::string node_name)
    : queue_(queue), node_(std::move(node_name)), thread_([this] { run(); }) {}

NodeEventLog::~NodeEventLog() {
  stop_.store(true);
  thread_.join();
  drain();
}

void NodeEventLog::drain() {
  // the thread and a final drain after the loop: one consumer at a time
  std::lock_guard<std::mutex> lock(consumer_);
  NodeEvent e;
  while (queue_.pop(e)) spdlog::log(level_of(e), "{}", format_event(e, node_));
  if (const uint64_t dropped = queue_.dropped(); dropped > dropped_reported_) {
    spdlog::warn("{}: {} events were not logged (the log did not keep up)", node_, dropped - dropped_reported_);
    dropped_reported_ = dropped;
  }
}

void NodeEventLog::run() {
  name_own_thread("events");
  while (!stop_.load()) {
    drain();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace teleop::runtime
