#include "bag_metadata.h"

#include <yaml-cpp/yaml.h>

#include "teleop/bag/bag_error.h"
#include "teleop/bag/bag_format.h"
#include "teleop/common/config.h"
#include "teleop/common/input_file.h"
#include "teleop/common/strict_yaml.h"

namespace teleop::bag {
namespace {

void emit_time(YAML::Emitter& out, const char* key, const char* unit, int64_t ns) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap << YAML::Key << unit << YAML::Value << ns << YAML::EndMap;
}

void emit_topic(YAML::Emitter& out, const TopicInfo& topic, uint64_t count) {
  out << YAML::BeginMap << YAML::Key << "topic_metadata" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << topic.name;
  out << YAML::Key << "type" << YAML::Value << topic.type;
  out << YAML::Key << "serialization_format" << YAML::Value << "cdr";
  // rosbag2 keeps the QoS profiles as one YAML text inside the YAML: a quoted string
  out << YAML::Key << "offered_qos_profiles" << YAML::Value << YAML::DoubleQuoted << topic.qos_profile;
  out << YAML::EndMap << YAML::Key << "message_count" << YAML::Value << count << YAML::EndMap;
}

// the `files` list (version 5): our one database, spanning the whole bag
void emit_files(YAML::Emitter& out, const BagSummary& s) {
  out << YAML::Key << "files" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
  out << YAML::Key << "path" << YAML::Value << s.db_file;
  emit_time(out, "starting_time", "nanoseconds_since_epoch", s.first_ns);
  emit_time(out, "duration", "nanoseconds", s.last_ns - s.first_ns);
  out << YAML::Key << "message_count" << YAML::Value << s.message_count;
  out << YAML::EndMap << YAML::EndSeq;
}

[[noreturn]] void fail(const std::string& path, const std::string& problem) { throw BagError(path + ": " + problem); }

// a metadata file comes with a recording from anywhere: read like a configuration (a regular
// file only, no alias bomb)
YAML::Node load(const std::string& path) {
  try {
    return parse_strict_yaml(read_input_file(path), path);
  } catch (const ConfigError& e) {
    throw BagError(e.what());
  } catch (const YAML::Exception& e) {
    fail(path, std::string("not readable as YAML (") + e.what() + ")");
  }
}

int check_version(const YAML::Node& info, const std::string& path) {
  const int version = info["version"].as<int>();
  if (version > kRosbag2MetadataVersion) {
    fail(path, "rosbag2 metadata version " + std::to_string(version) + " is newer than this reads (up to " +
                   std::to_string(kRosbag2MetadataVersion) + ")");
  }
  if (version < 1) fail(path, "rosbag2 metadata version " + std::to_string(version) + " is not valid");
  return version;
}

MetadataFile parse(const YAML::Node& root, const std::string& path) {
  const YAML::Node info = root["rosbag2_bagfile_information"];
  // an absent key gives an invalid node, which throws when asked IsMap()
  if (!info || !info.IsMap()) fail(path, "no rosbag2_bagfile_information (not a rosbag2 metadata file)");
  MetadataFile file;
  file.version = check_version(info, path);
  const auto storage = info["storage_identifier"].as<std::string>();
  if (storage != "sqlite3") fail(path, "storage " + storage + " is not sqlite3 (this reads sqlite3 bags only)");
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths.IsSequence() || paths.size() != 1) {
    fail(path, "relative_file_paths must name one database (split bags are not read)");
  }
  file.db_file = paths[0].as<std::string>();
  file.message_count = info["message_count"].as<uint64_t>();
  return file;
}

}  // namespace

std::string metadata_yaml(const BagSummary& s) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "rosbag2_bagfile_information" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << kRosbag2MetadataVersion;
  out << YAML::Key << "storage_identifier" << YAML::Value << "sqlite3";
  emit_time(out, "duration", "nanoseconds", s.last_ns - s.first_ns);
  emit_time(out, "starting_time", "nanoseconds_since_epoch", s.first_ns);
  out << YAML::Key << "message_count" << YAML::Value << s.message_count;
  out << YAML::Key << "topics_with_message_count" << YAML::Value << YAML::BeginSeq;
  for (size_t i = 0; i < s.topics.size(); ++i) emit_topic(out, s.topics[i], s.topic_counts[i]);
  out << YAML::EndSeq;
  out << YAML::Key << "compression_format" << YAML::Value << YAML::DoubleQuoted << "";
  out << YAML::Key << "compression_mode" << YAML::Value << YAML::DoubleQuoted << "";
  out << YAML::Key << "relative_file_paths" << YAML::Value << YAML::BeginSeq << s.db_file << YAML::EndSeq;
  emit_files(out, s);
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

MetadataFile read_metadata(const std::string& path) {
  const YAML::Node root = load(path);
  try {
    return parse(root, path);
  } catch (const YAML::Exception& e) {
    // a key missing or of the wrong type
    fail(path, std::string("malformed rosbag2 metadata (") + e.what() + ")");
  }
}

}  // namespace teleop::bag
