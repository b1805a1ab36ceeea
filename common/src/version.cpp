#include "teleop/common/version.h"

#include "teleop_version_info.h"

namespace teleop {

std::string version_text() { return std::string("teleop ") + TELEOP_VERSION + " (git " + TELEOP_GIT_DESCRIBE + ")"; }

}  // namespace teleop
