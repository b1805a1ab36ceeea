#pragma once
// The project's version, for `--version` on every executable and for reports.

#include <cstdint>
#include <string>

namespace teleop {

/// The version of what nodes say to each other, raised by hand when a message's meaning changes
/// (docs/versions.md). Peers of another protocol or message version stop (runtime/src/peer_agreement.h).
inline constexpr uint32_t kProtocolVersion = 1;

/// The first 12 hex digits of SHA-256 over idl/*.idl at configure time: any change of a message
/// changes it.
const char* message_version();

/// "0.1.0 (git a80a09a)".
std::string software_version();

/// "teleop 0.1.0 (git a80a09a)": the project version and `git describe` of the tree it was
/// configured from ("unknown" outside a git checkout).
std::string version_text();

}  // namespace teleop
