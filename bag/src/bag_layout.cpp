#include "bag_layout.h"

#include <filesystem>
#include <system_error>

#include "teleop/bag/bag_error.h"

namespace teleop::bag {

namespace fs = std::filesystem;

std::string db_file_name(const std::string& dir) {
  fs::path folder = fs::path(dir).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "run1/" names "run1"
  return folder.filename().string() + "_0.db3";
}

std::string path_in(const std::string& dir, const std::string& file) { return (fs::path(dir) / file).string(); }

std::string metadata_path(const std::string& dir) { return path_in(dir, "metadata.yaml"); }

void create_bag_dir(const std::string& dir) {
  if (dir.empty()) throw BagError("bag writer: no folder given");
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw BagError(dir + ": exists and is not a folder");
    if (!fs::is_empty(dir, ec)) throw BagError(dir + ": exists and is not empty (a bag is never written over)");
    return;
  }
  if (!fs::create_directories(dir, ec) && ec) throw BagError(dir + ": cannot create the folder (" + ec.message() + ")");
}

std::string sole_db_file(const std::string& dir) {
  std::string found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() != ".db3") continue;
    if (!found.empty()) return "";
    found = entry.path().filename().string();
  }
  return found;
}

}  // namespace teleop::bag
