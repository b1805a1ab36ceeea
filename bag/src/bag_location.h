#pragma once
// Finding a bag's database from its folder: through metadata.yaml when there is one, else by
// rosbag2's file name (or the folder's only *.db3, for a renamed bag).

#include <optional>
#include <string>

#include "bag_metadata.h"

namespace teleop::bag {

struct BagLocation {
  std::string db_path;
  std::optional<MetadataFile> metadata;  ///< absent when the folder has no metadata.yaml
};

/// Checks `dir` is a folder holding a bag and its metadata.yaml (if any) one we read; throws
/// BagError naming the folder or the file otherwise.
BagLocation locate_bag(const std::string& dir);

}  // namespace teleop::bag
