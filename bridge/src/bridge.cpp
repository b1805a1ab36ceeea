#include "teleop/bridge/bridge.h"

#include <chrono>
#include <thread>

#include "bridge_server.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/bus_tap.h"
#include "teleop/tools/message_schemas.h"

namespace teleop::bridge {

int run_bridge(const tools::BusOptions& bus, const BridgeOptions& options, FILE* log) {
  BridgeServer server(options, log);
  // a channel per topic as discovery finds it written, with the schema an MCAP recording embeds
  tools::BusTap tap(
      bus, "teleop_bridge", {},
      [&](const tools::TappedTopic& topic) {
        const bag::TopicInfo info = tools::recorded_topic(topic.name, *topic.type, "", tools::RecordingFormat::kMcap);
        std::fprintf(log, "advertising %s (%s)\n", topic.name.c_str(), info.type.c_str());
        return static_cast<int>(server.add_channel(topic.name, info.type, info.schema));
      },
      [&](int channel_id, const transport::RawSample& sample) {
        server.dispatch(static_cast<uint32_t>(channel_id), sample);
      });
  const uint16_t port = server.start();
  std::fprintf(log, "teleop bridge: listening on ws://%s:%u (domain %d, max rate %g Hz per subscription%s)\n",
               options.address.c_str(), static_cast<unsigned>(port), tap.domain_id(), options.max_rate_hz,
               options.max_rate_hz > 0 ? "" : ": unlimited");
  std::fflush(log);
  while (!runtime::shutdown_requested()) {
    tap.subscribe_new_topics();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  tap.close();  // no sample is dispatched after this
  server.stop();
  return 0;
}

}  // namespace teleop::bridge
