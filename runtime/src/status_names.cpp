#include "teleop/runtime/status_names.h"

namespace teleop::runtime {

const char* state_name(msg::NodeState state) {
  switch (state) {
    case msg::STATE_STARTING: return "starting";
    case msg::STATE_RUNNING: return "running";
    case msg::STATE_SAFE_HOLD: return "safe_hold";
    case msg::STATE_FAULT: return "fault";
    case msg::STATE_STOPPING: return "stopping";
  }
  return "unknown";
}

std::optional<msg::NodeState> state_from_name(std::string_view name) {
  for (const msg::NodeState s : kNodeStates) {
    if (name == state_name(s)) return s;
  }
  return std::nullopt;
}

const char* fault_name(uint32_t fault_code) {
  switch (fault_code) {
    case msg::FAULT_NONE: return "none";
    case msg::FAULT_PEER_LOST: return "peer_lost";
    case msg::FAULT_STALE_INPUT: return "stale_input";
    case msg::FAULT_COMMAND_REJECTED: return "command_rejected";
    case msg::FAULT_LOOP_OVERRUN: return "loop_overrun";
    case msg::FAULT_HARDWARE: return "hardware";
    case msg::FAULT_CONTACT_REFLEX: return "contact_reflex";
    case msg::FAULT_SPEED_REFLEX: return "speed_reflex";
    case msg::FAULT_NOT_IN_COMMAND: return "not_in_command";
    case msg::FAULT_EMERGENCY_STOP: return "emergency_stop";
    case msg::FAULT_VERSION_MISMATCH: return "version_mismatch";
    case msg::FAULT_ARCHITECTURE_MISMATCH: return "architecture_mismatch";
  }
  return "unknown_fault";
}

const char* refusal_name(uint32_t refusal) {
  switch (refusal) {
    case msg::REFUSAL_NONE: return "none";
    case msg::REFUSAL_OTHER_WRITER: return "other_writer";
    case msg::REFUSAL_NOT_ACCEPTED: return "not_accepted";
    case msg::REFUSAL_SEQUENCE_JUMP: return "sequence_jump";
    case msg::REFUSAL_INVALID: return "invalid";
  }
  return "unknown_refusal";
}

const char* role_name(msg::NodeRole role) {
  switch (role) {
    case msg::ROLE_LEADER: return "leader";
    case msg::ROLE_FOLLOWER: return "follower";
    case msg::ROLE_TWIN: return "twin";
    case msg::ROLE_TOOL: return "tool";
  }
  return "unknown";
}

}  // namespace teleop::runtime
