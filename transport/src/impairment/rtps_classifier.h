#pragma once
// Looks inside an RTPS message far enough to tell discovery traffic (SPDP/SEDP) from the rest,
// so impairment can leave discovery alone and experiments start from a matched state.

#include <cstdint>

namespace teleop::transport::impairment {

/// True when any submessage of the RTPS message is addressed to or from a built-in discovery
/// endpoint (participant or endpoint discovery). Liveliness (WLP) and user data are not
/// discovery. A malformed message counts as not discovery. Real-time safe.
bool is_discovery_message(const uint8_t* data, uint32_t size);

}  // namespace teleop::transport::impairment
