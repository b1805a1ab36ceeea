// Whether a leader's commands are in force, from what the node taking them says in its status.
#include "test_participant.h"
#include "teleop/runtime/command_authority.h"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/transport/publication.h"

namespace teleop::runtime {
namespace {

constexpr const char* kCommandTopic = "teleop/leader/joint_command";

transport::ParticipantConfig config(const std::string& name) { return test::local_participant(name, 150); }

bool wait_for(const std::function<bool()>& done) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

// the leader's command writer and its authority; a follower that says what it makes of it
struct Bus {
  transport::Participant leader_side{config("leader")};
  transport::Participant follower_side{config("follower")};
  transport::Publication<msg::JointCommand> command{leader_side, transport::topics::kLeaderCommand, "leader"};
  CommandAuthority authority{leader_side, command.writer_id(), "leader", kCommandTopic};
  transport::Publication<msg::NodeStatus> status{follower_side, transport::topics::kNodeStatus, "follower"};

  Bus() {
    auto& s = status.sample();
    s.role(msg::ROLE_FOLLOWER);
    s.state(msg::STATE_RUNNING);
    s.flows().emplace_back();
    s.flows().back().topic(kCommandTopic);
    s.flows().back().awaited(true);
  }
  msg::FlowStatus& flow() { return status.sample().flows().back(); }
  void follows_us() {
    flow().following("leader");
    flow().following_writer(command.writer_id().hex().data());
    flow().in_force(true);
  }
  // publishes the status and waits until the authority's verdict is `expected`
  bool says(CommandRefusal expected) {
    status.publish();
    return wait_for([&] {
      authority.poll(monotonic_now_ns());
      return authority.refusal() == expected;
    });
  }
};

TEST(CommandAuthority, NoTakerHeardOfIsNotInCommand) {
  Bus bus;
  bus.authority.poll(monotonic_now_ns());
  EXPECT_FALSE(bus.authority.in_command());
  EXPECT_EQ(bus.authority.refusal(), CommandRefusal::kNoTaker);
}

TEST(CommandAuthority, InCommandWhenTheTakerFollowsUsRunsAndHasOurCommandInForce) {
  Bus bus;
  bus.follows_us();
  ASSERT_TRUE(bus.says(CommandRefusal::kNone));
  EXPECT_TRUE(bus.authority.in_command());
  NodeEvent e;
  bool reported = false;
  while (bus.leader_side.events().pop(e)) reported = reported || e.kind == NodeEvent::Kind::kAuthority;
  EXPECT_TRUE(reported) << "coming into command is an event for the log";
}

TEST(CommandAuthority, SaysWhyNot) {
  Bus bus;
  bus.follows_us();
  ASSERT_TRUE(bus.says(CommandRefusal::kNone));

  // another node of the same name took over: the writer, not the name, decides
  bus.flow().following_writer("");
  ASSERT_TRUE(bus.says(CommandRefusal::kOtherWriter));
  EXPECT_EQ(bus.authority.taker().view(), "follower");
  EXPECT_EQ(bus.authority.detail().view(), "leader");

  bus.follows_us();
  bus.flow().in_force(false);
  bus.flow().refusal_detail("rejected_wrong_size");
  ASSERT_TRUE(bus.says(CommandRefusal::kInvalid));
  EXPECT_EQ(bus.authority.detail().view(), "rejected_wrong_size");

  bus.follows_us();
  bus.status.sample().state(msg::STATE_SAFE_HOLD);
  bus.status.sample().fault_codes({msg::FAULT_CONTACT_REFLEX});
  ASSERT_TRUE(bus.says(CommandRefusal::kHolding));
  EXPECT_EQ(bus.authority.detail().view(), "contact_reflex");

  bus.status.sample().state(msg::STATE_RUNNING);
  bus.status.sample().fault_codes({});
  bus.flow().following("rogue");
  bus.flow().following_writer("");
  bus.flow().refusal(msg::REFUSAL_NOT_ACCEPTED);
  bus.flow().refused_source("leader");
  ASSERT_TRUE(bus.says(CommandRefusal::kNotAccepted));
}

TEST(CommandAuthority, IgnoresNodesThatDoNotTakeItsCommands) {
  Bus bus;
  bus.follows_us();
  ASSERT_TRUE(bus.says(CommandRefusal::kNone));
  // a monitor-like node reading the topic without needing it, following someone else
  transport::Participant tool_side{config("tool")};
  transport::Publication<msg::NodeStatus> tool{tool_side, transport::topics::kNodeStatus, "tool"};
  tool.sample().flows().emplace_back();
  tool.sample().flows().back().topic(kCommandTopic);
  tool.sample().flows().back().awaited(false);
  tool.sample().flows().back().following("rogue");
  tool.publish();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  bus.authority.poll(monotonic_now_ns());
  EXPECT_TRUE(bus.authority.in_command());
}

}  // namespace
}  // namespace teleop::runtime
