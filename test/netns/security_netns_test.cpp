// DDS Security across "hosts" (network namespaces on a bridge), with a PKI made at test time by
// scripts/make_pki.sh: secure nodes work; a node without a valid identity gets nothing; a valid
// identity without permission for a topic can neither publish nor read it; the wire carries no
// plaintext joint values; bad security files stop a node at start with a message naming them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "netns_network.h"
#include "netns_nodes.h"

namespace teleop::test {
namespace {
namespace fs = std::filesystem;

constexpr int kLeaderHost = 0;
constexpr int kFollowerHost = 1;
constexpr int kProbeHost = 2;
constexpr double kRunS = 4;
// the leader's home position of its last joint, which it commands unchanged (amplitude 0): a
// known value to look for on the wire
constexpr double kSentinelRad = 0.123456789012345;

// a PKI made by scripts/make_pki.sh in the build tree (never committed), removed afterwards
class Pki {
 public:
  explicit Pki(const std::string& name)
      : dir_(
            (fs::path(TELEOP_BIN_DIR).parent_path() / ("pki-test-" + std::to_string(getpid()) + "-" + name)).string()) {
    const ProcessResult r = run_process({"/bin/bash", source("scripts/make_pki.sh"), dir_}, std::chrono::seconds(60));
    if (r.exit_status != 0) throw std::runtime_error("make_pki.sh failed: " + r.output);
  }
  ~Pki() { fs::remove_all(dir_); }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

YAML::Node security_section(const std::string& pki, const std::string& identity_dir) {
  YAML::Node s;
  s["identity_ca"] = pki + "/identity_ca.pem";
  s["identity_certificate"] = identity_dir + "/identity.pem";
  s["private_key"] = identity_dir + "/key.pem";
  s["permissions_ca"] = pki + "/permissions_ca.pem";
  s["governance"] = pki + "/governance.p7s";
  s["permissions"] = identity_dir + "/permissions.p7s";
  return s;
}

void set_sentinel(YAML::Node& root) { root["leader"]["home_rad"][6] = kSentinelRad; }

class SecurityNetns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      pki_ = new Pki("main");
      rogue_pki_ = new Pki("rogue");  // same layout, its own CAs: what an outsider can make
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
  static void TearDownTestSuite() {
    delete pki_;
    delete rogue_pki_;
  }

  void SetUp() override {
    const std::string reason = netns_unavailable_reason();
    // never a silent pass or skip: without namespaces this test fails and says why
    ASSERT_TRUE(reason.empty()) << reason;
    ASSERT_TRUE(pki_ != nullptr && rogue_pki_ != nullptr) << "scripts/make_pki.sh failed (see above)";
    network_ = std::make_unique<NetnsNetwork>(3);
    nodes_ = std::make_unique<NetnsNodes>(*network_);
  }

  void TearDown() override {
    if (HasFailure() && nodes_) std::cerr << nodes_->outputs();
  }

  // unicast peers between the three hosts; security from `pki` for `identity` (a node folder)
  YAML::Node transport(int host, const std::string& pki = "", const std::string& identity = "") const {
    YAML::Node t;
    t["domain_id"] = 0;
    t["interface_whitelist"].push_back(network_->address(host));
    t["discovery"]["mode"] = "peers";
    for (int h : {kLeaderHost, kFollowerHost, kProbeHost}) {
      if (h != host) t["initial_peers"].push_back(network_->address(h));
    }
    if (!pki.empty()) t["security"] = security_section(pki, identity);
    return t;
  }
  YAML::Node secure(int host, const std::string& node) const {
    return transport(host, pki_->dir(), pki_->dir() + "/" + node);
  }

  // runs leader and follower for kRunS with the given transports; both must exit cleanly
  void run_pair(const YAML::Node& leader, const YAML::Node& follower) {
    nodes_->start("follower", kFollowerHost, follower, kRunS + 1);
    ASSERT_TRUE(nodes_->process("follower").wait_for_output("starting", std::chrono::seconds(20))) << nodes_->outputs();
    nodes_->start("leader", kLeaderHost, leader, kRunS, set_sentinel);
    ASSERT_EQ(nodes_->wait_exit("leader", std::chrono::seconds(30)), 0) << nodes_->outputs();
    ASSERT_EQ(nodes_->wait_exit("follower", std::chrono::seconds(30)), 0) << nodes_->outputs();
  }

  // a node that must refuse to start: it exits non-zero, saying `message`
  void expect_refused_start(const YAML::Node& transport, const std::string& message) {
    nodes_->start("leader", kLeaderHost, transport, kRunS);
    const auto status = nodes_->wait_exit("leader", std::chrono::seconds(30));
    const std::string output = nodes_->process("leader").output();
    ASSERT_TRUE(status.has_value()) << "the node ran with bad security files\n" << output;
    EXPECT_NE(*status, 0) << output;
    EXPECT_NE(output.find(message), std::string::npos) << "expected: " << message << "\n" << output;
  }

  // a follower with its own identity, and teleop_topic_probe beside it with `identity`'s files;
  // returns what the probe printed
  std::string run_probe_beside_follower(const std::string& role, const std::string& identity) {
    nodes_->start("follower", kFollowerHost, secure(kFollowerHost, "follower"), kRunS + 1);
    EXPECT_TRUE(nodes_->process("follower").wait_for_output("starting", std::chrono::seconds(20))) << nodes_->outputs();
    // it holds `identity`'s certificate and speaks as that node (the follower also checks names)
    const std::string config = nodes_->write_config(role, "probe", secure(kProbeHost, identity),
                                                    [&](YAML::Node& root) { root["node"]["name"] = identity; });
    nodes_->start_program("probe", kProbeHost,
                          {bin("teleop_topic_probe"), "--config", config, "--domain", std::to_string(nodes_->domain()),
                           "--duration", std::to_string(kRunS - 1)});
    EXPECT_EQ(nodes_->wait_exit("probe", std::chrono::seconds(30)), 0) << nodes_->outputs();
    EXPECT_EQ(nodes_->wait_exit("follower", std::chrono::seconds(30)), 0) << nodes_->outputs();
    return nodes_->process("probe").output();
  }

  static Pki* pki_;
  static Pki* rogue_pki_;
  std::unique_ptr<NetnsNetwork> network_;
  std::unique_ptr<NetnsNodes> nodes_;
};

Pki* SecurityNetns::pki_ = nullptr;
Pki* SecurityNetns::rogue_pki_ = nullptr;

// (1)
TEST_F(SecurityNetns, SecureNodesWorkEndToEnd) {
  run_pair(secure(kLeaderHost, "leader"), secure(kFollowerHost, "follower"));
  EXPECT_NE(nodes_->process("leader").output().find("security on"), std::string::npos);
  const auto commands = received(nodes_->report("follower"), "teleop/leader/joint_command");
  const auto states = received(nodes_->report("leader"), "teleop/follower/joint_state");
  // the secure handshake takes 1-3 s of the 4 s run on this VM (longer under load), so the
  // claim is not a count of a full run: once matched, both streams flow, decrypted (a quarter
  // second's worth at least). Their rate and loss are the loops' (a loaded ASan build skipped
  // cycles, streamed at 377 Hz and its reader's history overflowed: 9 % lost), which the
  // benchmarks measure, not this test.
  for (const auto& [what, rx] : {std::pair{"commands", commands}, std::pair{"states", states}}) {
    EXPECT_GE(rx.received, 250u) << what << " did not flow between secure nodes";
  }
  EXPECT_EQ(nodes_->report("leader").final_state, "running");
}

// Sets an environment variable for the processes this test starts; restores it at the end.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// (2) an identity from another CA: the node starts (its own files are consistent) but the
// others never authenticate it, so nothing flows either way
TEST_F(SecurityNetns, NodeWithoutValidIdentityReceivesNothing) {
  // rejecting the rogue's handshakes leaks inside Fast DDS 2.9 (test/netns/fastdds_lsan.supp);
  // in a sanitizer build, suppress exactly that stack (full unwinding, so the stack reaches
  // Fast DDS through libcrypto); harmless elsewhere
  const char* asan = std::getenv("ASAN_OPTIONS");
  const ScopedEnv unwind("ASAN_OPTIONS", std::string(asan ? asan : "") + ":fast_unwind_on_malloc=0");
  const ScopedEnv suppress("LSAN_OPTIONS", "suppressions=" + source("test/netns/fastdds_lsan.supp"));
  const std::string rogue = rogue_pki_->dir();
  run_pair(secure(kLeaderHost, "leader"), transport(kFollowerHost, rogue, rogue + "/follower"));
  EXPECT_EQ(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 0u);
  EXPECT_EQ(received(nodes_->report("leader"), "teleop/follower/joint_state").received, 0u);
  EXPECT_EQ(nodes_->report("follower").final_state, "starting") << "the rogue follower saw a leader";
}

// (3) the twin's identity is valid but grants neither publishing nor reading joint commands
TEST_F(SecurityNetns, ValidIdentityWithoutPermissionCanNeitherPublishNorRead) {
  const std::string probe = run_probe_beside_follower("twin", "twin");
  EXPECT_NE(probe.find("publish teleop/leader/joint_command: refused"), std::string::npos) << probe;
  EXPECT_NE(probe.find("read teleop/leader/joint_command: refused"), std::string::npos) << probe;
  EXPECT_EQ(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 0u);
}

// the control for (3): with the leader's identity the same probe publishes and the follower
// receives, so the refusal above is the permissions' doing
TEST_F(SecurityNetns, ProbeWithPermissionPublishesToTheFollower) {
  const std::string probe = run_probe_beside_follower("leader", "leader");
  EXPECT_NE(probe.find("publish teleop/leader/joint_command: sent"), std::string::npos) << probe;
  // the leader publishes commands but may not read them
  EXPECT_NE(probe.find("read teleop/leader/joint_command: refused"), std::string::npos) << probe;
  EXPECT_GT(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 0u);
}

// (4) a capture on the bridge holds the sentinel joint value only when security is off
std::string sentinel_bytes() {
  std::string bytes(sizeof(double), '\0');
  std::memcpy(bytes.data(), &kSentinelRad, sizeof(double));  // CDR little endian on this host
  return bytes;
}

// runs leader and follower while tcpdump records the bridge; returns the capture
std::string captured_run(const NetnsNetwork& network, const NetnsNodes& nodes, const std::function<void()>& run) {
  const std::string pcap = nodes.dir() + "/bridge.pcap";
  RunningProcess tcpdump({system_tool("tcpdump"), "-i", network.bridge(), "-U", "-s", "0", "-w", pcap});
  EXPECT_TRUE(tcpdump.wait_for_output("listening on", std::chrono::seconds(10))) << tcpdump.output();
  run();
  EXPECT_EQ(tcpdump.stop(SIGTERM, std::chrono::seconds(10)), 0) << tcpdump.output();
  return read_file(pcap);
}

TEST_F(SecurityNetns, CaptureShowsNoPlaintextJointValuesWithEncryption) {
  const std::string wire = captured_run(
      *network_, *nodes_, [&] { run_pair(secure(kLeaderHost, "leader"), secure(kFollowerHost, "follower")); });
  ASSERT_GE(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 1000u)
      << "no commands flowed: the capture would prove nothing";
  EXPECT_GT(wire.size(), 100'000u) << "the capture missed the traffic";
  EXPECT_EQ(wire.find(sentinel_bytes()), std::string::npos) << "the sentinel joint value is readable on the wire";
}

TEST_F(SecurityNetns, CaptureShowsPlaintextJointValuesWithoutSecurity) {
  const std::string wire =
      captured_run(*network_, *nodes_, [&] { run_pair(transport(kLeaderHost), transport(kFollowerHost)); });
  ASSERT_GE(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 1000u);
  EXPECT_NE(wire.find(sentinel_bytes()), std::string::npos)
      << "the sentinel is not in the capture: the search is blind";
}

// (5)
TEST_F(SecurityNetns, ExpiredCertificateStopsTheNodeNamingTheFile) {
  const std::string expired = nodes_->dir() + "/expired";
  const ProcessResult made =
      run_process({"/bin/bash", source("test/netns/make_expired_identity.sh"), pki_->dir(), "leader", expired},
                  std::chrono::seconds(30));
  ASSERT_EQ(made.exit_status, 0) << made.output;
  fs::copy_file(pki_->dir() + "/leader/permissions.p7s", expired + "/permissions.p7s");
  expect_refused_start(transport(kLeaderHost, pki_->dir(), expired),
                       "security.identity_certificate " + expired + "/identity.pem: certificate has expired");
}

TEST_F(SecurityNetns, TamperedPermissionsStopTheNodeNamingTheFile) {
  // grant the twin everything by editing its signed permissions
  const std::string twin = nodes_->dir() + "/twin";
  fs::copy(pki_->dir() + "/twin", twin);
  std::string text = read_file(twin + "/permissions.p7s");
  const std::string granted = "<topic>teleop/twin/joint_state</topic>";
  ASSERT_NE(text.find(granted), std::string::npos);
  text.replace(text.find(granted), granted.size(), "<topic>*</topic>");
  write_file(twin + "/permissions.p7s", text);
  expect_refused_start(transport(kLeaderHost, pki_->dir(), twin),
                       "security.permissions " + twin + "/permissions.p7s: signature does not verify");
}

TEST_F(SecurityNetns, CertificateFromAnotherCaStopsTheNodeNamingTheFile) {
  const std::string foreign = rogue_pki_->dir() + "/leader";
  // both CAs are called the same, so OpenSSL finds "the" issuer and its signature fails
  expect_refused_start(transport(kLeaderHost, pki_->dir(), foreign),
                       "security.identity_certificate " + foreign + "/identity.pem: certificate signature failure " +
                           "(verified against identity_ca " + pki_->dir() + "/identity_ca.pem)");
}

}  // namespace
}  // namespace teleop::test
