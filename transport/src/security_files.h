#pragma once
// Checks a node's DDS Security files before Fast DDS sees them, so a bad file stops the node
// with a message that names it (Fast DDS itself only reports that the participant failed).

#include <stdexcept>

#include "teleop/transport/participant_config.h"

namespace teleop::transport {

/// A security file that cannot be used: unreadable, malformed, expired, not signed by its CA,
/// tampered with. The message names the file and says what is wrong with it.
class SecurityFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Verifies the identity certificate against the identity CA (signature and validity dates),
/// that the private key belongs to it, and the S/MIME signatures of governance and permissions
/// against the permissions CA. Setup time only. Throws SecurityFileError.
void verify_security_files(const SecurityConfig& security);

}  // namespace teleop::transport
