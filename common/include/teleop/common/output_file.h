#pragma once
// Files a program writes its results to (a node's report and trace), checked before the work whose
// results they hold: a path that cannot be written is a configuration error at start, not a lost
// result at the end. Configuration time only: throws.

#include <string>

namespace teleop {

/// Checks that `path` can be opened for writing as its writer will open it later (created when
/// missing), without blocking (a FIFO nobody reads is refused) and without changing it: a file
/// the check had to create is removed again, an existing one is left as it was. Throws ConfigError
/// "<flag> <path>: cannot be written: <reason>", `flag` being where the path came from (`--trace`).
void check_output_file(const std::string& path, const std::string& flag);

}  // namespace teleop
