// `teleop bridge` against real nodes, read by the Foxglove WebSocket client library
// (test/bridge/ws_interop/bridge_client.mjs, npm @foxglove/ws-protocol, installed by
// scripts/setup.sh into TELEOP_NPM_DIR): the follower's joint states decode live with the schema
// the bridge advertised, no more arrive than --max-rate allows, the follower's scene is computed
// for the 3D panel (--scene), and a client that stops reading has its frames dropped and counted
// while another client is served at full rate.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <regex>

#include "process_helpers.h"
#include "tool_processes.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

// domains 200..230: the lead's process tests spread over 100..199 (unique_domain)
int bridge_domain() { return 200 + static_cast<int>(getpid() % 31); }

class BridgeProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(TELEOP_NPM_DIR "/node_modules/@foxglove/ws-protocol"))
        << "no @foxglove/ws-protocol in " TELEOP_NPM_DIR "/node_modules: run scripts/setup.sh (it installs the "
           "test's npm packages)";
  }

  std::string dir = make_temp_dir();
  int domain = bridge_domain();
  RunningProcess follower{node(dir, "follower", domain, 60)};
  RunningProcess leader{node(dir, "leader", domain, 60)};

  // a bridge on a free port; its URL once it listens and advertises the follower's state
  std::string start(RunningProcess& bridge) {
    if (!bridge.wait_for_output("advertising teleop/follower/joint_state", 30s)) return "";
    std::smatch m;
    const std::string& out = bridge.output();
    return std::regex_search(out, m, std::regex(R"(listening on (ws://127\.0\.0\.1:[0-9]+))")) ? m[1].str() : "";
  }

  // the client script on the follower's joint states; through env: the spawn takes a path, env
  // finds node on PATH (and execs it: a signal to the process reaches node)
  static std::vector<std::string> client_command(const std::string& url, std::vector<std::string> args) {
    std::vector<std::string> argv{"/usr/bin/env", "TELEOP_NPM_DIR=" TELEOP_NPM_DIR, "node", TELEOP_BRIDGE_CLIENT, url,
                                  "--topic", "teleop/follower/joint_state", "--source", "follower", "--seconds", "3"};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  }
};

unsigned long long json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\":([0-9]+)"))) return 0;
  return std::stoull(m[1]);
}

TEST_F(BridgeProcessTest, JointStatesDecodeLiveWithinTheRateLimitBesideTheScene) {
  RunningProcess bridge(tool({"bridge", "--port", "0", "--max-rate", "50", "--scene", "follower"}, domain));
  const std::string url = start(bridge);
  ASSERT_FALSE(url.empty()) << bridge.output();

  const ProcessResult r = run_process(client_command(url, {"--max-rate", "50", "--scene"}), 90s);
  ASSERT_EQ(r.exit_status, 0) << r.output << bridge.output();
  EXPECT_GT(json_number(r.output, "received"), 0u) << r.output;
  // the leader's and the follower's topics at least, and the scene's three
  EXPECT_GE(json_number(r.output, "channels"), 6u) << r.output;
  EXPECT_GE(json_number(r.output, "scene_frames"), 7u) << r.output;  // the arm's links

  ASSERT_EQ(bridge.stop(SIGINT, 10s), 0) << bridge.output();
  // the bridge's own tally agrees: the 1 kHz stream was mostly held back, nothing dropped
  std::smatch m;
  const std::string& out = bridge.output();
  ASSERT_TRUE(std::regex_search(out, m, std::regex(R"(left: sent ([0-9]+), dropped ([0-9]+) \(queue full\), limited ([0-9]+))")))
      << out;
  EXPECT_GT(std::stoull(m[3]), std::stoull(m[1])) << out;
}

TEST_F(BridgeProcessTest, AClientThatStopsReadingLosesFramesNotTheOthers) {
  RunningProcess bridge(tool({"bridge", "--port", "0", "--max-rate", "0", "--queue", "64"}, domain));
  const std::string url = start(bridge);
  ASSERT_FALSE(url.empty()) << bridge.output();

  RunningProcess client(client_command(url, {"--stall"}));
  ASSERT_TRUE(client.wait_for_output("stalled client subscribed", 60s)) << client.output() << bridge.output();
  // flow, not time: however long the stalled client's socket buffers take to fill, its queue
  // overflows at last and the bridge says so
  ASSERT_TRUE(bridge.wait_for_output("is not keeping up", 150s)) << bridge.output();
  client.process().signal(SIGUSR1);  // now the reading client is measured beside the stalled one
  ASSERT_TRUE(client.wait_for_output("\"received\"", 60s)) << client.output() << bridge.output();
  EXPECT_EQ(client.stop(0, 10s), 0) << client.output();  // signal 0: no signal, it exits by itself
  EXPECT_GT(json_number(client.output(), "received"), 0u) << client.output();

  ASSERT_EQ(bridge.stop(SIGINT, 10s), 0) << bridge.output();
  // two clients left: the stalled one dropped frames (counted), the reading one got its share
  const std::regex tally(R"(left: sent ([0-9]+), dropped ([0-9]+) \(queue full\))");
  const std::string& out = bridge.output();
  unsigned long long most_dropped = 0, clients = 0;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), tally); it != std::sregex_iterator(); ++it, ++clients) {
    most_dropped = std::max(most_dropped, std::stoull((*it)[2]));
  }
  EXPECT_EQ(clients, 2u) << out;
  EXPECT_GT(most_dropped, 0u) << out;
}

}  // namespace
}  // namespace teleop::test
