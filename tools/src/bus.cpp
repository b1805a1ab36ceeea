#include "bus.h"

#include <spdlog/fmt/fmt.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/participant_config.h"

namespace teleop::tools {

Bus::Bus(const BusOptions& options, const std::string& name)
    : options_(options),
      participant_(std::make_unique<transport::Participant>(
          transport::tool_participant_config(options.config_path, options.domain_id, name), &graph_)) {}

std::optional<TopicView> Bus::wait_for_writers(const std::string& topic) const {
  const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(options_.discovery_s * 1e9);
  while (!runtime::shutdown_requested()) {
    for (TopicView& t : topics()) {
      if (t.name == topic && !t.writers.empty()) return std::move(t);
    }
    if (monotonic_now_ns() > deadline_ns) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

const transport::SampleType& Bus::type_of(const TopicView& topic) {
  if (topic.types.size() != 1) {
    std::string types;
    for (const auto& t : topic.types) types += (types.empty() ? "" : ", ") + t;
    throw std::runtime_error(fmt::format("{}: its endpoints disagree on the type ({})", topic.name, types));
  }
  const transport::SampleType* type = transport::find_sample_type(topic.types.front());
  if (type == nullptr) {
    throw std::runtime_error(fmt::format("{}: type {} is not a teleop type (idl/)", topic.name, topic.types.front()));
  }
  return *type;
}

void Bus::listen() const {
  const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(options_.discovery_s * 1e9);
  while (!runtime::shutdown_requested() && monotonic_now_ns() < deadline_ns) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::string no_writer_message(const std::string& topic, const Bus& bus) {
  return fmt::format("no writer on {} in domain {} within {:g} s (`teleop topic list` shows what there is)", topic,
                     bus.domain_id(), bus.options().discovery_s);
}

}  // namespace teleop::tools
