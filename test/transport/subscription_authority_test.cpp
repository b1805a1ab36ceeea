// What a stream subscription follows and refuses, through real participants in one process: a
// subscription bound to named nodes refuses the others' samples, another writer is refused while
// the followed one talks, an invalid newest sample is not in force; the first refusal of each kind
// per writer becomes one event for the node's log, and the flow's status says all of it.
#include <gtest/gtest.h>

#include <vector>

#include "in_process_bus.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::transport {
namespace {

using test_bus::config;
using test_bus::stream_topic;
using test_bus::wait_for;

std::vector<NodeEvent> drain(Participant& p) {
  std::vector<NodeEvent> events;
  NodeEvent e;
  while (p.events().pop(e)) events.push_back(e);
  return events;
}

// each publication writes `n` samples, one poll after each round
void write_rounds(std::vector<Publication<msg::JointState>*> pubs, Subscription<msg::JointState>& sub, int n) {
  for (int i = 0; i < n; ++i) {
    for (auto* p : pubs) ASSERT_TRUE(p->publish());
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    sub.poll();
  }
}

TEST(SubscriptionAuthority, ABoundSubscriptionRefusesOtherNodesAndLogsTheFirstRefusalOnce) {
  Participant leader_side(config("leader_side"));
  Participant rogue_side(config("rogue_side"));
  Participant reader_side(config("reader_side"));
  const auto topic = stream_topic("bound");
  Publication<msg::JointState> leader(leader_side, topic, "leader");
  Publication<msg::JointState> rogue(rogue_side, topic, "rogue");
  Subscription<msg::JointState> sub(reader_side, topic);
  sub.accept_only({"leader"});
  ASSERT_TRUE(wait_for([&] { return sub.reader().matched() == 2 && leader.matched() == 1 && rogue.matched() == 1; }));

  // the rogue first: refused although nobody is followed yet
  write_rounds({&rogue}, sub, 20);
  EXPECT_FALSE(sub.has_sample());
  write_rounds({&leader, &rogue}, sub, 20);
  ASSERT_TRUE(wait_for([&] {
    sub.poll();
    return sub.has_sample();
  }));
  EXPECT_EQ(sub.latest().header().source().to_string(), "leader");
  EXPECT_GE(sub.refused_not_accepted(), 30u);
  const FlowAuthority& a = sub.reader().authority();
  EXPECT_EQ(a.following.view(), "leader");
  EXPECT_EQ(a.following_writer.view(), std::string_view(leader.writer_id().hex().data()));
  EXPECT_TRUE(a.in_force);
  EXPECT_EQ(a.refused_source.view(), "rogue");
  EXPECT_EQ(a.refusal, msg::REFUSAL_NOT_ACCEPTED);

  const std::vector<NodeEvent> events = drain(reader_side);
  int refusals = 0, follows = 0;
  for (const NodeEvent& e : events) {
    if (e.kind == NodeEvent::Kind::kRefused) {
      ++refusals;
      EXPECT_EQ(e.who.view(), "rogue");
      EXPECT_EQ(e.code, static_cast<int32_t>(msg::REFUSAL_NOT_ACCEPTED));
    }
    if (e.kind == NodeEvent::Kind::kFollowing) {
      ++follows;
      EXPECT_EQ(e.who.view(), "leader");
      EXPECT_EQ(e.count, 1u);
    }
  }
  EXPECT_EQ(refusals, 1) << "the first refusal of the kind is logged, the others counted";
  EXPECT_EQ(follows, 1);
}

TEST(SubscriptionAuthority, AnotherWriterIsRefusedWhileTheFollowedOneTalks) {
  Participant leader_side(config("leader_side2"));
  Participant rogue_side(config("rogue_side2"));
  Participant reader_side(config("reader_side2"));
  const auto topic = stream_topic("unbound");
  Publication<msg::JointState> leader(leader_side, topic, "leader");
  Publication<msg::JointState> rogue(rogue_side, topic, "rogue");
  Subscription<msg::JointState> sub(reader_side, topic);
  ASSERT_TRUE(wait_for([&] { return sub.reader().matched() == 2 && leader.matched() == 1 && rogue.matched() == 1; }));
  write_rounds({&leader}, sub, 5);
  ASSERT_TRUE(wait_for([&] {
    sub.poll();
    return sub.has_sample();
  }));
  write_rounds({&leader, &rogue}, sub, 50);
  EXPECT_EQ(sub.latest().header().source().to_string(), "leader");
  EXPECT_EQ(sub.session().session(), 1u);
  EXPECT_GT(sub.session().refused_other_writer(), 0u);
  const FlowAuthority& a = sub.reader().authority();
  EXPECT_EQ(a.refused[msg::REFUSAL_OTHER_WRITER], sub.session().refused_other_writer());
  EXPECT_EQ(a.refusal, msg::REFUSAL_OTHER_WRITER);
  bool logged = false;
  for (const NodeEvent& e : drain(reader_side)) {
    if (e.kind != NodeEvent::Kind::kRefused) continue;
    EXPECT_FALSE(logged) << "once per writer and kind";
    logged = true;
    EXPECT_EQ(e.who.view(), "rogue");
    EXPECT_EQ(e.detail.view(), "leader") << "whom the flow follows instead";
  }
  EXPECT_TRUE(logged);
}

TEST(SubscriptionAuthority, AnInvalidNewestSampleIsNotInForceUntilAValidOneComes) {
  Participant writer_side(config("writer_side3"));
  Participant reader_side(config("reader_side3"));
  const auto topic = stream_topic("invalid");
  Publication<msg::JointState> leader(writer_side, topic, "leader");
  Subscription<msg::JointState> sub(reader_side, topic);
  ASSERT_TRUE(wait_for([&] { return sub.reader().matched() == 1 && leader.matched() == 1; }));
  write_rounds({&leader}, sub, 3);
  ASSERT_TRUE(wait_for([&] { return sub.poll() > 0 || sub.has_sample(); }));
  sub.reject_latest(0, "wrong_size");
  sub.reject_latest(0, "wrong_size");
  const FlowAuthority& a = sub.reader().authority();
  EXPECT_FALSE(a.in_force);
  EXPECT_EQ(sub.rejected(), 2u);
  EXPECT_EQ(a.refusal, msg::REFUSAL_INVALID);
  EXPECT_EQ(a.refusal_detail.view(), "wrong_size");
  int logged = 0;
  for (const NodeEvent& e : drain(reader_side)) logged += e.kind == NodeEvent::Kind::kRefused ? 1 : 0;
  EXPECT_EQ(logged, 1);
  ASSERT_TRUE(leader.publish());
  ASSERT_TRUE(wait_for([&] { return sub.poll() > 0; }));
  EXPECT_TRUE(a.in_force) << "a new sample of the followed writer is in force until the node says otherwise";
}

}  // namespace
}  // namespace teleop::transport
