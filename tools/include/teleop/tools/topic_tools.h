#pragma once
// `teleop topic list|info|echo|hz`: the bus as a user sees it, on any domain and discovery setup
// the nodes use (the transport section of a node config: domain, peers, discovery servers,
// security).

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

namespace teleop::tools {

/// How a tool joins the bus.
struct BusOptions {
  /// A node config whose transport section to use; empty: the defaults.
  std::string config_path;
  std::optional<int> domain_id;
  /// How long to listen to discovery before answering (list, info) or before giving up on a
  /// topic without writers (echo, hz) [s].
  double discovery_s = 2.0;
};

int topic_list(const BusOptions& bus, bool verbose, FILE* out);
int topic_info(const BusOptions& bus, const std::string& topic, FILE* out);

struct EchoOptions {
  std::string topic;
  /// Print only this field (dotted path); empty: the whole sample.
  std::string field;
  /// Stop after this many samples (0: until interrupted).
  uint64_t count = 0;
};
int topic_echo(const BusOptions& bus, const EchoOptions& options, FILE* out);

struct HzOptions {
  std::string topic;
  /// Arrivals the rate and period statistics are computed over.
  size_t window = 1000;
  /// Stop after this many samples (0: until interrupted or `duration_s`).
  uint64_t count = 0;
  double duration_s = 0.0;
};
/// Prints a line a second and a total at the end. Returns 0, or 1 when nothing arrived.
int topic_hz(const BusOptions& bus, const HzOptions& options, FILE* out);

}  // namespace teleop::tools
