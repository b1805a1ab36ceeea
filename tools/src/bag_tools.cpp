#include "teleop/tools/bag_tools.h"

#include <spdlog/fmt/fmt.h>

#include <filesystem>
#include <map>

#include "teleop/bag/bag_reader.h"
#include "teleop/bag/bag_writer.h"
#include "teleop/bag/mcap_writer.h"
#include "teleop/bag/recording_copy.h"

namespace teleop::tools {

std::string bag_info(const std::string& path) {
  bag::BagReader reader(path);
  std::map<int, uint64_t> counts;
  bag::BagMessage m;
  while (reader.next(m)) ++counts[m.topic_id];
  const double duration_s = static_cast<double>(reader.end_ns() - reader.start_ns()) * 1e-9;
  std::string text = fmt::format("path:     {}\nformat:   {}\nduration: {:.3f} s\nmessages: {}\ntopics:   {}\n",
                                 reader.db_path(), reader.format(), duration_s, reader.message_count(),
                                 reader.topics().size());
  for (size_t i = 0; i < reader.topics().size(); ++i) {
    const bag::TopicInfo& t = reader.topics()[i];
    const uint64_t count = counts[static_cast<int>(i) + 1];
    const double rate = duration_s > 0 ? static_cast<double>(count) / duration_s : 0.0;
    text += fmt::format("  {} ({}): {} messages, {:.1f} Hz{}\n", t.name, t.type.empty() ? "no type" : t.type, count,
                        rate, t.schema.empty() ? "" : ", schema " + t.schema_encoding);
  }
  if (!reader.warning().empty()) text += "warning:  " + reader.warning() + "\n";
  return text;
}

bool is_recording(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return true;
  if (!fs::is_directory(path, ec)) return false;
  if (fs::exists(fs::path(path) / "metadata.yaml", ec)) return true;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    if (entry.path().extension() == ".db3") return true;
  }
  return false;
}

std::string recording_stem(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

RecordingFormat format_of_path(const std::string& path) {
  const std::string ext = ".mcap";
  const bool mcap = path.size() > ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
  return mcap ? RecordingFormat::kMcap : RecordingFormat::kSqlite3;
}

uint64_t convert_recording(const std::string& in, const std::string& out, RecordingFormat format) {
  bag::BagReader reader(in);
  const auto mapping = [format](const bag::TopicInfo& t) { return topic_for(t, format); };
  if (format == RecordingFormat::kMcap) {
    bag::McapWriter writer({out});
    return bag::copy_recording(reader, writer, mapping);
  }
  bag::BagWriter writer({out});
  return bag::copy_recording(reader, writer, mapping);
}

}  // namespace teleop::tools
