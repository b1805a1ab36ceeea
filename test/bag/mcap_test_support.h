#pragma once
// Shared by the MCAP units: a recording of known messages written with McapWriter, and reading
// a file's bytes.

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bag_test_support.h"
#include "teleop/bag/mcap_writer.h"

namespace teleop::bag::test {

inline TopicInfo typed_topic(const std::string& name) {
  return {name, "teleop_msgs/msg/" + name, "- depth: 1\n", "int32 x\n", "ros2msg"};
}

/// `count` messages of 300 bytes alternating on topics "a" and "b", recv_ns 1'000'000 * (i + 1),
/// publish_ns 10 less; `chunk_bytes` small makes many chunks.
inline void record_mcap(const std::string& path, int count, McapCompression compression = McapCompression::kZstd,
                        size_t chunk_bytes = 4096) {
  McapWriterOptions options;
  options.path = path;
  options.compression = compression;
  options.chunk_bytes = chunk_bytes;
  McapWriter writer(options);
  const int a = writer.add_topic(typed_topic("a"));
  const int b = writer.add_topic(typed_topic("b"));
  for (int i = 0; i < count; ++i) {
    const auto data = payload(300, static_cast<uint32_t>(i));
    MessageToWrite m;
    m.topic_id = i % 2 == 0 ? a : b;
    m.recv_ns = 1'000'000LL * (i + 1);
    m.publish_ns = m.recv_ns - 10;
    m.data = data.data();
    m.size = data.size();
    writer.write(m);
  }
  writer.close();
}

inline std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes, size_t count) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(count));
}

}  // namespace teleop::bag::test
