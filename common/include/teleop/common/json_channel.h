#pragma once
// Messages computed as JSON for a named channel with a schema: what one part computes (view's
// scene for Foxglove's 3D panel) and another serves (teleop bridge), without either knowing the
// other (cli/ wires them).

#include <cstddef>
#include <cstdint>
#include <string>

namespace teleop {

struct JsonChannel {
  std::string topic;
  /// What a viewer knows the messages by ("foxglove.FrameTransforms").
  std::string schema_name;
  /// A JSON Schema of the messages.
  std::string schema;
};

struct JsonMessage {
  /// Index into its source's channels.
  size_t channel = 0;
  std::string json;
  /// When the newest data it shows was taken (CLOCK_REALTIME ns).
  int64_t stamp_ns = 0;
};

}  // namespace teleop
