// What a node judges in its peers' statuses: another release, or (of this release) another
// teleoperation architecture, is a disagreement; a peer or a node that plays none, a tool's status
// and its own status are not.
#include "peer_agreement.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "test_participant.h"
#include "teleop/common/clock.h"
#include "teleop/common/version.h"
#include "teleop/transport/publication.h"

namespace teleop::runtime {
namespace {

using namespace std::chrono_literals;

transport::ParticipantConfig config(const std::string& name) { return test::local_participant(name, 150); }

// a node of this release (or another) that says what it plays
class Peer {
 public:
  explicit Peer(const std::string& name) : participant_(config(name)), status_(participant_, transport::topics::kNodeStatus, name) {
    status_.sample().protocol_version(kProtocolVersion);
    status_.sample().message_version(message_version());
  }
  Peer& plays(const std::string& architecture) {
    status_.sample().architecture(architecture);
    return *this;
  }
  Peer& of_protocol(uint32_t protocol) {
    status_.sample().protocol_version(protocol);
    return *this;
  }
  // says it until the node has judged it
  void say(const PeerAgreement& node) {
    const uint64_t before = node.statuses_judged();
    const auto end = std::chrono::steady_clock::now() + 10s;
    while (node.statuses_judged() == before && std::chrono::steady_clock::now() < end) {
      (void)status_.publish();
      std::this_thread::sleep_for(20ms);
    }
    ASSERT_GT(node.statuses_judged(), before) << "the node never heard the peer";
  }

 private:
  transport::Participant participant_;
  transport::Publication<msg::NodeStatus> status_;
};

struct Node {
  transport::Participant participant{config("follower")};
  PeerAgreement agreement;
  explicit Node(const std::string& architecture) : agreement(participant, "follower", architecture) {}
  bool mismatched(Disagreement what) const { return agreement.mismatched(what, monotonic_now_ns()); }
};

TEST(PeerAgreement, APeerOfAnotherArchitectureIsNamedWithWhatItPlays) {
  Node node("position_position");
  Peer("leader").plays("pfc_tdpa").say(node.agreement);
  EXPECT_TRUE(node.mismatched(Disagreement::kArchitecture));
  EXPECT_FALSE(node.mismatched(Disagreement::kVersion));
  PeerMismatch words;
  ASSERT_TRUE(node.agreement.last_mismatch(Disagreement::kArchitecture, words));
  EXPECT_EQ(words.peer.view(), "leader");
  EXPECT_EQ(words.peer_architecture.view(), "pfc_tdpa");
}

TEST(PeerAgreement, ThePeersOfTheSameArchitectureOrOfNoneAgree) {
  Node node("mmt");
  Peer("leader").plays("mmt").say(node.agreement);
  Peer("hand").say(node.agreement);  // the hand's CAN node plays none
  EXPECT_FALSE(node.mismatched(Disagreement::kArchitecture));
  EXPECT_FALSE(node.mismatched(Disagreement::kVersion));
}

TEST(PeerAgreement, ANodeThatPlaysNoneJudgesNoArchitecture) {
  Node node("");
  Peer("leader").plays("pfc").say(node.agreement);
  EXPECT_FALSE(node.mismatched(Disagreement::kArchitecture));
}

TEST(PeerAgreement, AnotherReleaseIsAVersionMismatchWhateverItsArchitectureSays) {
  Node node("pfc");
  Peer("old_leader").of_protocol(kProtocolVersion + 1).plays("garbage").say(node.agreement);
  EXPECT_TRUE(node.mismatched(Disagreement::kVersion));
  EXPECT_FALSE(node.mismatched(Disagreement::kArchitecture)) << "what follows another release's versions means nothing";
}

TEST(PeerAgreement, AToolsStatusSaysNothing) {
  Node node("pfc");
  Peer("topic_pub").of_protocol(0).plays("mmt").say(node.agreement);
  EXPECT_FALSE(node.mismatched(Disagreement::kVersion));
  EXPECT_FALSE(node.mismatched(Disagreement::kArchitecture));
}

}  // namespace
}  // namespace teleop::runtime
