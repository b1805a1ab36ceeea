#pragma once
// The follower's side of a leader under test: reads the leader's commands on `topic`, publishes
// the follower's state, and says in its status that it follows the leader's commands once they
// arrive (a leader runs only while its commands are in force).

#include <teleop/msg/arm.h>

#include "teleop/transport/joint_fields.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"
#include "teleop/transport/topics.h"

namespace teleop::test {

template <typename Command>
struct FollowingPeer {
  transport::Subscription<Command> command;
  transport::Publication<msg::JointState> state;
  transport::Publication<msg::NodeStatus> status;

  FollowingPeer(transport::Participant& p, const transport::TopicSpec<Command>& topic, size_t joints)
      : command(p, topic), state(p, transport::topics::kFollowerState, "follower"),
        status(p, transport::topics::kNodeStatus, "follower") {
    transport::presize_joint_state(state.sample(), joints);
    status.sample().role(msg::ROLE_FOLLOWER);
    status.sample().state(msg::STATE_RUNNING);
    status.sample().flows().emplace_back();
    status.sample().flows().back().topic(topic.name);
    status.sample().flows().back().awaited(true);
    status.sample().flows().back().in_force(true);
  }
  // publishes the state, and the status once the leader's commands arrive
  bool publish() {
    command.poll();
    if (command.has_sample()) {
      auto& flow = status.sample().flows().back();
      flow.following("leader");
      flow.following_writer(command.session().writer().hex().data());
      if (!status.publish()) return false;
    }
    return state.publish();
  }
};

}  // namespace teleop::test
