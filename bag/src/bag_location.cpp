#include "bag_location.h"

#include <filesystem>
#include <system_error>

#include "bag_layout.h"
#include "teleop/bag/bag_error.h"

namespace teleop::bag {
namespace {

namespace fs = std::filesystem;

bool is_file(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

// without metadata.yaml: the name rosbag2 gives the database, else the folder's only *.db3
std::string find_db_alone(const std::string& dir) {
  const std::string named = path_in(dir, db_file_name(dir));
  if (is_file(named)) return named;
  const std::string sole = sole_db_file(dir);
  if (sole.empty()) {
    throw BagError(dir + ": not a bag (no metadata.yaml, no " + db_file_name(dir) + ", no single *.db3)");
  }
  return path_in(dir, sole);
}

}  // namespace

BagLocation locate_bag(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw BagError(dir + (fs::exists(dir, ec) ? ": not a folder (a bag is a folder)" : ": no such folder"));
  }
  BagLocation location;
  const std::string metadata = metadata_path(dir);
  if (!is_file(metadata)) {
    location.db_path = find_db_alone(dir);
    return location;
  }
  location.metadata = read_metadata(metadata);
  location.db_path = path_in(dir, location.metadata->db_file);
  if (!is_file(location.db_path)) {
    throw BagError(location.db_path + ": missing (metadata.yaml names it as the bag's database)");
  }
  return location;
}

}  // namespace teleop::bag
