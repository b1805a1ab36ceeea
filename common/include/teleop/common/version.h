#pragma once
// The project's version, for `--version` on every executable and for reports.

#include <string>

namespace teleop {

/// "teleop 0.1.0 (git a80a09a)": the project version and `git describe` of the tree it was
/// configured from ("unknown" outside a git checkout).
std::string version_text();

}  // namespace teleop
