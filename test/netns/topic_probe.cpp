// teleop_topic_probe: a participant that tries to publish joint commands and to read them, as
// any node could, with the transport section of a node config (e.g. another role's identity).
// Prints one line per attempt: "publish <topic>: refused" / "publish <topic>: sent N, matched M",
// "read <topic>: refused" / "read <topic>: received N". Exits 0 when it ran, 2 on a bad config.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/participant_config.h"
#include "teleop/transport/publication.h"

namespace {

using namespace teleop;

constexpr auto kTopic = transport::topics::kLeaderCommand;

// a program holding a node's identity speaks as that node (its node.name, which a follower checks)
std::optional<transport::Publication<msg::JointCommand>> try_publication(transport::Participant& participant,
                                                                       const std::string& node_name) {
  try {
    return std::optional<transport::Publication<msg::JointCommand>>(std::in_place, participant, kTopic, node_name);
  } catch (const std::runtime_error& e) {
    std::printf("publish %s: refused (%s)\n", kTopic.name, e.what());
    return std::nullopt;
  }
}

std::optional<transport::Reader<msg::JointCommand>> try_reader(transport::Participant& participant) {
  try {
    return participant.make_reader(kTopic);
  } catch (const std::runtime_error& e) {
    std::printf("read %s: refused (%s)\n", kTopic.name, e.what());
    return std::nullopt;
  }
}

int run(const std::string& config_path, int domain, double duration_s) {
  const ConfigNode root = ConfigNode::load_file(config_path);
  transport::ParticipantConfig config = transport::parse_participant_config(root.child("transport"), "probe");
  config.domain_id = domain;
  transport::Participant participant(config);
  auto publication = try_publication(participant, root.child("node").get_string("name", "probe"));
  auto reader = try_reader(participant);
  msg::JointCommand received;
  uint64_t received_count = 0;
  if (publication) transport::presize(7, publication->sample().q_des_rad(), publication->sample().dq_des_radps());
  const int64_t end_ns = monotonic_now_ns() + static_cast<int64_t>(duration_s * 1e9);
  while (monotonic_now_ns() < end_ns) {
    if (publication) publication->publish();
    while (reader && reader->take_next(received)) ++received_count;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (publication) {
    std::printf("publish %s: sent %llu, matched %d\n", kTopic.name,
                static_cast<unsigned long long>(publication->sent()), publication->matched());
  }
  if (reader) std::printf("read %s: received %llu\n", kTopic.name, static_cast<unsigned long long>(received_count));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tries to publish and read teleop/leader/joint_command with a node config's transport"};
  std::string config;
  int domain = 0;
  double duration_s = 3;
  app.add_option("--config", config, "node config whose transport section (identity) is used")->required();
  app.add_option("--domain", domain, "DDS domain")->required();
  app.add_option("--duration", duration_s, "seconds to publish and read");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(config, domain, duration_s);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "config error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe: %s\n", e.what());
    return 1;
  }
}
