// teleop_discovery_churn: participants that join a domain and leave it again, over and over, as
// another lab's nodes starting and stopping on the same network would (franka_ros2 #201: a 1 kHz
// loop broken by another machine's nodes starting). Each participant reads the follower's state,
// wrench and status, so that every join is matched by the follower's writers and every leave
// unmatched. Prints "joined churn_I" as each participant is up (on a starved host a round can take
// longer than a storm) and "round N: P participants up" once a round's are. Exits 0 when done.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "teleop/transport/participant.h"

namespace {

using namespace teleop;

struct Visitor {
  transport::Participant participant;
  transport::Reader<msg::JointState> state;
  transport::Reader<msg::WrenchStamped> wrench;
  transport::Reader<msg::NodeStatus> status;

  explicit Visitor(const transport::ParticipantConfig& config)
      : participant(config),
        state(participant.make_reader(transport::topics::kFollowerState)),
        wrench(participant.make_reader(transport::topics::kFollowerWrench)),
        status(participant.make_reader(transport::topics::kNodeStatus)) {}
};

int run(int domain, int participants, double duration_s, int up_ms, int down_ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(duration_s);
  for (int round = 1; std::chrono::steady_clock::now() < end; ++round) {
    std::vector<std::unique_ptr<Visitor>> up;
    for (int i = 0; i < participants; ++i) {
      transport::ParticipantConfig c;
      c.domain_id = domain;
      c.name = "churn_" + std::to_string(i);
      c.shm = false;
      // as Fast DDS's default (20 s) and longer than a round: the peers' lease timers for these
      // participants never run while they come and go. With teleop's 3 s, the thirty leaving at
      // once raced those timers and Fast DDS 2.9 aborted the churn in most storms
      // (PDP::check_remote_participant_liveliness, docs/reliability.md)
      c.participant_lease_ns = 20'000'000'000;
      up.push_back(std::make_unique<Visitor>(c));
      std::printf("joined %s\n", c.name.c_str());
      std::fflush(stdout);
    }
    std::printf("round %d: %d participants up\n", round, participants);
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::milliseconds(up_ms));
    up.clear();
    std::this_thread::sleep_for(std::chrono::milliseconds(down_ms));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"participants that join a domain and leave it, over and over"};
  int domain = 0;
  int participants = 30;
  double duration_s = 10;
  int up_ms = 500;
  int down_ms = 250;
  app.add_option("--domain", domain, "DDS domain")->required();
  app.add_option("--participants", participants, "participants per round")->check(CLI::Range(1, 200));
  app.add_option("--duration", duration_s, "seconds to keep churning")->check(CLI::PositiveNumber);
  app.add_option("--up-ms", up_ms, "how long each round's participants stay")->check(CLI::Range(1, 60000));
  app.add_option("--down-ms", down_ms, "pause between rounds")->check(CLI::Range(0, 60000));
  CLI11_PARSE(app, argc, argv);
  try {
    return run(domain, participants, duration_s, up_ms, down_ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop_discovery_churn: %s\n", e.what());
    return 1;
  }
}
