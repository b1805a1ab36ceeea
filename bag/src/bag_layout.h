#pragma once
// Where the files of a bag folder are: <dir>/metadata.yaml and <dir>/<dir-name>_0.db3, as rosbag2
// names them.

#include <string>

namespace teleop::bag {

/// The database's file name for a bag folder: "runs/run1/" -> "run1_0.db3".
std::string db_file_name(const std::string& dir);
/// `file` inside the folder `dir`.
std::string path_in(const std::string& dir, const std::string& file);
/// "<dir>/metadata.yaml"
std::string metadata_path(const std::string& dir);

/// Creates the folder of a new bag; throws BagError when it exists and is not empty (a bag is
/// never written over) or cannot be created.
void create_bag_dir(const std::string& dir);

/// The one *.db3 file in `dir`, "" when there is none or several (a renamed bag without its
/// metadata.yaml).
std::string sole_db_file(const std::string& dir);

}  // namespace teleop::bag
