#include "teleop/bridge/bridge.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "bridge_server.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/bus_tap.h"
#include "teleop/tools/message_schemas.h"

namespace teleop::bridge {
namespace {

// how often discovery is asked for new topics
constexpr int64_t kDiscoveryPeriodNs = 100'000'000;

// a computed source's channels on the server and when it is polled next
struct ComputedFeed {
  ComputedSource source;
  std::vector<uint32_t> channel_ids;
  int64_t period_ns = 0;
  int64_t next_ns = 0;
};

std::vector<ComputedFeed> add_computed(BridgeServer& server, std::vector<ComputedSource> sources, FILE* log) {
  std::vector<ComputedFeed> feeds;
  for (ComputedSource& source : sources) {
    ComputedFeed feed;
    for (const JsonChannel& c : source.channels) {
      feed.channel_ids.push_back(server.add_channel({0, c.topic, c.schema_name, c.schema, "json", "jsonschema"}));
      std::fprintf(log, "advertising %s (%s, computed)\n", c.topic.c_str(), c.schema_name.c_str());
    }
    feed.period_ns = static_cast<int64_t>(1e9 / std::max(source.rate_hz, 0.1));
    feed.source = std::move(source);
    feeds.push_back(std::move(feed));
  }
  return feeds;
}

void poll(BridgeServer& server, ComputedFeed& feed, int64_t now_ns, std::vector<JsonMessage>& messages) {
  if (now_ns < feed.next_ns) return;
  feed.next_ns = now_ns + feed.period_ns;
  messages.clear();
  feed.source.poll(messages);
  for (const JsonMessage& m : messages) {
    if (m.channel >= feed.channel_ids.size()) continue;
    server.publish(feed.channel_ids[m.channel], reinterpret_cast<const uint8_t*>(m.json.data()), m.json.size(),
                   m.stamp_ns);
  }
}

}  // namespace

int run_bridge(const tools::BusOptions& bus, const BridgeOptions& options, FILE* log,
               std::vector<ComputedSource> sources) {
  BridgeServer server(options, log);
  // a channel per topic as discovery finds it written, with the schema an MCAP recording embeds
  tools::BusTap tap(
      bus, "teleop_bridge", {},
      [&](const tools::TappedTopic& topic) {
        const bag::TopicInfo info = tools::recorded_topic(topic.name, *topic.type, "", tools::RecordingFormat::kMcap);
        std::fprintf(log, "advertising %s (%s)\n", topic.name.c_str(), info.type.c_str());
        return static_cast<int>(server.add_channel({0, topic.name, info.type, info.schema}));
      },
      [&](int channel_id, const transport::RawSample& sample) {
        server.publish(static_cast<uint32_t>(channel_id), sample.cdr.data(), sample.cdr.size(), sample.reception_ns);
      });
  std::vector<ComputedFeed> feeds = add_computed(server, std::move(sources), log);
  const uint16_t port = server.start();
  std::fprintf(log, "teleop bridge: listening on ws://%s:%u (domain %d, max rate %g Hz per subscription%s)\n",
               options.address.c_str(), static_cast<unsigned>(port), tap.domain_id(), options.max_rate_hz,
               options.max_rate_hz > 0 ? "" : ": unlimited");
  std::fflush(log);
  std::vector<JsonMessage> messages;
  int64_t next_discovery_ns = 0;
  while (!runtime::shutdown_requested()) {
    const int64_t now_ns = monotonic_now_ns();
    if (now_ns >= next_discovery_ns) {
      tap.subscribe_new_topics();
      next_discovery_ns = now_ns + kDiscoveryPeriodNs;
    }
    for (ComputedFeed& feed : feeds) poll(server, feed, now_ns, messages);
    std::this_thread::sleep_for(std::chrono::milliseconds(feeds.empty() ? 100 : 5));
  }
  tap.close();  // no sample is published after this
  server.stop();
  return 0;
}

}  // namespace teleop::bridge
