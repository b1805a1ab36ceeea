#pragma once
// metadata.yaml: the summary rosbag2 reads before opening the database (its version 5, as
// ROS 2 Humble writes it), docs/recording.md.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/bag/bag_types.h"

namespace teleop::bag {

/// What metadata.yaml says about a bag.
struct BagSummary {
  std::string db_file;                 ///< the database, relative to the bag's folder
  std::vector<TopicInfo> topics;       ///< by id (topics[id - 1])
  std::vector<uint64_t> topic_counts;  ///< messages per topic, in the order of `topics`
  uint64_t message_count = 0;
  int64_t first_ns = 0;  ///< smallest timestamp, 0 without messages
  int64_t last_ns = 0;   ///< largest timestamp
};

/// The summary as metadata.yaml text (rosbag2_bagfile_information, version 5, storage sqlite3).
std::string metadata_yaml(const BagSummary& summary);

/// The parts of a metadata.yaml the reader uses.
struct MetadataFile {
  int version = 0;
  std::string db_file;         ///< the one entry of relative_file_paths
  uint64_t message_count = 0;  ///< as the recorder last wrote it (stale after a kill)
};

/// Reads a metadata.yaml and checks it describes a bag we read: a version up to
/// kRosbag2MetadataVersion, storage sqlite3, one database file. Throws BagError naming the file.
MetadataFile read_metadata(const std::string& path);

}  // namespace teleop::bag
