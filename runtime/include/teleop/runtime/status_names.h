#pragma once
// Names of node states and fault codes for logs, reports and tools.

#include <cstdint>
#include <optional>
#include <string_view>

#include <teleop/msg/status.h>

namespace teleop::runtime {

/// Every msg::NodeState, in the IDL's order.
inline constexpr msg::NodeState kNodeStates[] = {msg::STATE_STARTING, msg::STATE_RUNNING, msg::STATE_SAFE_HOLD,
                                                 msg::STATE_FAULT, msg::STATE_STOPPING};

const char* state_name(msg::NodeState state);
/// The state called `name` by state_name(); nullopt for any other text (e.g. "unknown").
std::optional<msg::NodeState> state_from_name(std::string_view name);
const char* fault_name(uint32_t fault_code);
/// Why a flow refused a sample (msg::REFUSAL_*, FlowStatus.refusal).
const char* refusal_name(uint32_t refusal);
const char* role_name(msg::NodeRole role);

}  // namespace teleop::runtime
