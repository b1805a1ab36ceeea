#include "teleop/common/version.h"

#include "teleop_version_info.h"

namespace teleop {

std::string software_version() { return std::string(TELEOP_VERSION) + " (git " + TELEOP_GIT_DESCRIBE + ")"; }

std::string version_text() { return "teleop " + software_version(); }

const char* message_version() { return TELEOP_MESSAGE_VERSION; }

}  // namespace teleop
