#include "node_event_log.h"

#include <gtest/gtest.h>

#include <vector>

namespace teleop::runtime {
namespace {

class ScriptedLogic : public NodeLogic {
 public:
  void cycle(const CycleTick&) override {}
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override { faults.insert(faults.end(), faults_.begin(), faults_.end()); }
  void fill_report(NodeReport&) const override {}

  msg::NodeState state_ = msg::STATE_STARTING;
  std::vector<uint32_t> faults_;
};

std::vector<std::string> lines(NodeEventQueue& q) {
  std::vector<std::string> out;
  NodeEvent e;
  while (q.pop(e)) out.push_back(format_event(e, "follower"));
  return out;
}

TEST(StateWatch, RecordsEachChangeOfStateOrFaultsOnceWithItsCause) {
  NodeEventQueue q;
  StateWatch watch(q);
  ScriptedLogic logic;
  PacerStats loop;
  CycleTick tick;
  const auto cycle = [&](int64_t ms) {
    tick.deadline_ns = tick.now_ns = ms * 1'000'000;
    ++tick.index;
    return watch.after_cycle(tick, logic, loop);
  };
  EXPECT_TRUE(cycle(1)) << "the first state is news";
  EXPECT_FALSE(cycle(2));
  logic.state_ = msg::STATE_RUNNING;
  EXPECT_TRUE(cycle(3));
  EXPECT_FALSE(cycle(4));
  logic.state_ = msg::STATE_SAFE_HOLD;
  logic.faults_ = {msg::FAULT_STALE_INPUT};
  EXPECT_TRUE(cycle(5));
  logic.faults_ = {msg::FAULT_STALE_INPUT, msg::FAULT_CONTACT_REFLEX};
  EXPECT_TRUE(cycle(6)) << "a new fault while holding is news too";
  EXPECT_EQ(lines(q), (std::vector<std::string>{"follower: starting", "follower: starting -> running",
                                                 "follower: running -> safe_hold (stale_input)",
                                                 "follower: safe_hold -> safe_hold (stale_input, contact_reflex)"}));
}

TEST(StateWatch, RecordsAStallOfTheLoopWithItsLength) {
  NodeEventQueue q;
  StateWatch watch(q);
  ScriptedLogic logic;
  PacerStats loop;
  CycleTick tick{0, 1'000'000, 1'000'000};
  (void)watch.after_cycle(tick, logic, loop);
  (void)lines(q);
  loop.skipped = 1499;
  tick = CycleTick{1, 1'501'000'000, 1'501'000'000};
  (void)watch.after_cycle(tick, logic, loop);
  EXPECT_EQ(lines(q), std::vector<std::string>{"follower: the loop stalled for 1.500 s (1499 deadlines skipped)"});
}

TEST(FormatEvent, SaysWhomAFlowFollowsAndWhyItRefusesAWriter) {
  NodeEvent e;
  e.kind = NodeEvent::Kind::kFollowing;
  e.topic.assign("teleop/leader/joint_command");
  e.who.assign("leader");
  e.count = 2;
  EXPECT_EQ(format_event(e, "follower"), "follower: teleop/leader/joint_command follows 'leader' (session 2)");
  e.kind = NodeEvent::Kind::kRefused;
  e.who.assign("rogue");
  e.code = static_cast<int32_t>(msg::REFUSAL_OTHER_WRITER);
  e.detail.assign("leader");
  EXPECT_EQ(format_event(e, "follower"),
            "follower: teleop/leader/joint_command refuses samples of 'rogue': another writer is followed ('leader'); "
            "further ones are counted in its status");
  e.code = static_cast<int32_t>(msg::REFUSAL_INVALID);
  e.detail.assign("rejected_wrong_size");
  EXPECT_NE(format_event(e, "follower").find("invalid (rejected_wrong_size)"), std::string::npos);
}

TEST(NodeEventLog, LogsWhatIsQueuedAndCountsWhatWasDropped) {
  NodeEventQueue q;
  NodeEvent e;
  for (int i = 0; i < 300; ++i) (void)q.push(e);  // 256 fit
  EXPECT_EQ(q.dropped(), 44u);
  {
    NodeEventLog log(q, "follower");
    log.drain();
  }
  EXPECT_FALSE(q.pop(e)) << "drained";
}

}  // namespace
}  // namespace teleop::runtime
