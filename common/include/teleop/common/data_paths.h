#pragma once
// Where teleop's data is (config/, the plotting package), found the same way whether the running
// executable is in a build tree or installed under any prefix. It lets a command name a scenario,
// a node configuration or a network profile instead of giving its path (`teleop launch demo`,
// `teleop_follower --config follower`, `--impair follower=wan-35ms`). docs/install.md.

#include <filesystem>
#include <string>
#include <vector>

namespace teleop {

/// The places teleop's data is looked for, in this order.
struct DataRoots {
  /// <folder of the running executable>/../share/teleop: an installed teleop, whatever its
  /// prefix (the Debian package's /usr, `cmake --install --prefix` anywhere). First, so that an
  /// installed executable never reads the source tree it happened to be built from.
  std::filesystem::path beside_executable;
  /// The source tree this build was configured from (compiled in): a build tree's executables,
  /// whose ../share/teleop does not exist.
  std::filesystem::path source;
  /// <install prefix>/share/teleop as configured (compiled in): an executable run from elsewhere.
  std::filesystem::path configured_install;

  /// This process's roots: from /proc/self/exe and the paths compiled in.
  static DataRoots current();
};

/// Where `installed` (a path below share/teleop) or `in_source` (the same data's path in the
/// source tree) is looked for, in order: beside the executable, in the source tree, at the
/// configured install prefix.
std::vector<std::filesystem::path> data_candidates(const std::string& installed, const std::string& in_source,
                                                   const DataRoots& roots);

/// The folders of data_candidates(), comma-separated: where an error says it looked.
std::string data_candidates_text(const std::string& installed, const std::string& in_source, const DataRoots& roots);

/// The first of data_candidates() that exists (a file or a folder); empty when none does.
std::filesystem::path find_data(const std::string& installed, const std::string& in_source,
                                const DataRoots& roots = DataRoots::current());

/// A configuration file by name: config/<kind>/<name>.yaml (kind: "scenarios", "nodes", "network",
/// "experiments", "sweeps", ...): the first regular file among data_candidates(); "<name>.yaml" is
/// accepted as a name too.
/// Empty when there is none, or when `name` has a folder in it (that is a path, not a name).
std::filesystem::path find_named_config(const std::string& kind, const std::string& name,
                                        const DataRoots& roots = DataRoots::current());

/// A configuration file given by path or by name: `name_or_path` unchanged when it exists or has
/// a folder in it (a path: reading it reports what is wrong with it), else
/// find_named_config(kind, name_or_path). Throws ConfigError saying where it looked when a name
/// names nothing, and which shipped name it may have meant ("folower" -> "follower").
std::string resolve_config(const std::string& kind, const std::string& name_or_path,
                           const DataRoots& roots = DataRoots::current());

}  // namespace teleop
