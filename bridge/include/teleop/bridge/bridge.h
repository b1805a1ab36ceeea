#pragma once
// `teleop bridge`: the bus live in Foxglove or Lichtblick. A WebSocket server speaking the Foxglove
// WebSocket protocol (foxglove.websocket.v1) advertises every teleop topic with a writer on the
// domain as a channel (messages CDR, schema the type's ROS 2 .msg text, as MCAP recordings carry
// it) and streams the samples as received to the clients that subscribe (docs/tools.md).
// Read-only: clients cannot publish. The bridge only reads the bus: a slow or dead client loses
// frames from its own bounded queue and never slows the bus or another client.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "teleop/common/json_channel.h"
#include "teleop/tools/topic_tools.h"

namespace teleop::bridge {

struct BridgeOptions {
  /// Where to listen: loopback unless told otherwise (the bus is not for everyone to read).
  std::string address = "127.0.0.1";
  /// 0: a port the system chooses (printed).
  uint16_t port = 8765;
  /// Messages per second per subscription at most; 0: every sample.
  double max_rate_hz = 50.0;
  /// Frames waiting per client at most; beyond, the oldest is dropped and counted.
  size_t queue_capacity = 1024;
  /// Bytes the WebSocket library may hold for a client beyond the kernel's buffer before the
  /// bridge stops handing it frames (they wait in the bounded queue instead).
  size_t max_buffered_bytes = 256 * 1024;
};

/// Channels the bridge computes instead of relaying: JSON messages of schemas Foxglove knows by
/// name (the arms in the 3D panel: foxglove.FrameTransforms, foxglove.SceneUpdate). What computes
/// them is wired in by the caller (cli: view's scene), so the bridge knows no model.
struct ComputedSource {
  std::vector<JsonChannel> channels;
  /// How often poll() is called [Hz].
  double rate_hz = 30.0;
  /// Called on the bridge's main thread (never a Fast DDS thread), `rate_hz` times a second:
  /// appends the messages due now.
  std::function<void(std::vector<JsonMessage>& out)> poll;
};

/// Serves until interrupted (SIGINT, SIGTERM). Logs the address, each client's arrival and, when
/// it leaves, what it was sent, dropped and held back by the rate limit. Returns the exit code.
/// Throws std::runtime_error when the address cannot be bound, ConfigError on a bad node config.
/// `sources`: channels computed beside the bus's.
int run_bridge(const tools::BusOptions& bus, const BridgeOptions& options, FILE* log,
               std::vector<ComputedSource> sources = {});

}  // namespace teleop::bridge
