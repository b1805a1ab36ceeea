#pragma once
// Which release a node's status says it speaks (docs/versions.md): its protocol and message
// versions, first after the header of every NodeStatus.

#include <string_view>

#include <teleop/msg/status.h>

#include "teleop/common/version.h"

namespace teleop::runtime {

/// The status says its versions (0: a tool's or a test's own status, which says nothing).
inline bool says_its_release(const msg::NodeStatus& status) { return status.protocol_version() != 0; }

/// The status's node speaks this build's protocol and messages.
inline bool speaks_this_release(const msg::NodeStatus& status) {
  return status.protocol_version() == kProtocolVersion &&
         std::string_view(status.message_version().c_str()) == message_version();
}

}  // namespace teleop::runtime
