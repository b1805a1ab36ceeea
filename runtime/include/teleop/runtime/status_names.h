#pragma once
// Names of node states and fault codes for logs, reports and tools.

#include <cstdint>

#include <teleop/msg/status.h>

namespace teleop::runtime {

const char* state_name(msg::NodeState state);
const char* fault_name(uint32_t fault_code);
const char* role_name(msg::NodeRole role);

}  // namespace teleop::runtime
