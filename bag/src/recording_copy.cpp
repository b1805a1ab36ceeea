#include "teleop/bag/recording_copy.h"

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <vector>

namespace teleop::bag {

uint64_t copy_recording(BagReader& reader, RecordingWriter& writer, const TopicMapping& mapping) {
  std::vector<int> topic_ids;  // the writer's id of each of the reader's topics
  for (const TopicInfo& topic : reader.topics()) topic_ids.push_back(writer.add_topic(mapping ? mapping(topic) : topic));
  reader.select({});
  BagMessage m;
  uint64_t copied = 0;
  while (reader.next(m)) {
    MessageToWrite out;
    out.topic_id = topic_ids.at(static_cast<size_t>(m.topic_id - 1));
    out.recv_ns = m.recv_ns;
    out.recv_mono_ns = m.recv_mono_ns;
    out.publish_ns = m.publish_ns;
    out.writer = m.writer;
    out.data = m.data.data();
    out.size = m.data.size();
    writer.write(out);
    ++copied;
  }
  writer.close();
  return copied;
}

uint64_t repair_mcap(const std::string& path, McapCompression compression) {
  BagReader reader(path);
  if (reader.format().find("mcap") != 0) throw BagError(path + ": not an MCAP file (only MCAP files are repaired)");
  const std::string repaired = path + ".repair";
  std::error_code ec;
  std::filesystem::remove(repaired, ec);  // left by a repair that was itself interrupted
  uint64_t kept = 0;
  try {
    McapWriterOptions options;
    options.path = repaired;
    options.compression = compression;
    McapWriter writer(options);
    kept = copy_recording(reader, writer);
  } catch (...) {
    std::filesystem::remove(repaired, ec);
    throw;
  }
  std::filesystem::rename(repaired, path, ec);
  if (ec) throw BagError(repaired + ": cannot be renamed over " + path + " (" + ec.message() + ")");
  return kept;
}

}  // namespace teleop::bag
