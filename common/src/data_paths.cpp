#include "teleop/common/data_paths.h"

#include "teleop/common/config.h"
#include "teleop/common/did_you_mean.h"

namespace teleop {
namespace fs = std::filesystem;

DataRoots DataRoots::current() {
  DataRoots roots;
  std::error_code ec;
  // the executable's own path with symbolic links resolved: a link to it in ~/bin still finds
  // the prefix it was installed into
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.beside_executable = self.parent_path().parent_path() / "share" / "teleop";
  roots.source = TELEOP_DATA_SOURCE_DIR;
  roots.configured_install = TELEOP_DATA_INSTALL_DIR;
  return roots;
}

std::vector<fs::path> data_candidates(const std::string& installed, const std::string& in_source,
                                      const DataRoots& roots) {
  std::vector<fs::path> out;
  if (!roots.beside_executable.empty()) out.push_back(roots.beside_executable / installed);
  if (!roots.source.empty()) out.push_back(roots.source / in_source);
  if (!roots.configured_install.empty()) out.push_back(roots.configured_install / installed);
  return out;
}

std::string data_candidates_text(const std::string& installed, const std::string& in_source, const DataRoots& roots) {
  std::string text;
  for (const fs::path& candidate : data_candidates(installed, in_source, roots)) {
    text += (text.empty() ? "" : ", ") + candidate.parent_path().lexically_normal().string();
  }
  return text;
}

fs::path find_data(const std::string& installed, const std::string& in_source, const DataRoots& roots) {
  std::error_code ec;
  for (const fs::path& candidate : data_candidates(installed, in_source, roots)) {
    if (fs::exists(candidate, ec)) return candidate.lexically_normal();
  }
  return {};
}

namespace {

// config/<kind>/<name>.yaml, or empty when `name` is not a plain name
std::string config_file(const std::string& kind, const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") return {};
  const std::string file = fs::path(name).extension() == ".yaml" ? name : name + ".yaml";
  return "config/" + kind + "/" + file;
}

// the names of the configs of `kind` in every folder looked in: what a mistyped name may have meant
std::vector<std::string> known_names(const std::string& kind, const DataRoots& roots) {
  const std::string folder = "config/" + kind;
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::path& dir : data_candidates(folder, folder, roots)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
    }
  }
  return names;
}

}  // namespace

fs::path find_named_config(const std::string& kind, const std::string& name, const DataRoots& roots) {
  const std::string file = config_file(kind, name);
  if (file.empty()) return {};
  std::error_code ec;
  for (const fs::path& candidate : data_candidates(file, file, roots)) {
    if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal();
  }
  return {};
}

std::string resolve_config(const std::string& kind, const std::string& name_or_path, const DataRoots& roots) {
  std::error_code ec;
  const std::string file = config_file(kind, name_or_path);
  // a path, or a file of that name here, is the caller's: reading it says what is wrong with it
  if (file.empty() || (fs::exists(name_or_path, ec) && !fs::is_directory(name_or_path, ec))) return name_or_path;
  // a folder here does not hide the config of that name: in the source tree, `follower/` is the
  // node's code and `--config follower` its config
  const fs::path named = find_named_config(kind, name_or_path, roots);
  if (!named.empty()) return named.string();
  if (fs::exists(name_or_path, ec)) return name_or_path;  // the reader says it is a folder
  throw ConfigError(name_or_path + ": no such file, nor a name in " + data_candidates_text(file, file, roots) +
                    did_you_mean(fs::path(name_or_path).stem().string(), known_names(kind, roots)));
}

}  // namespace teleop
