// The twin's side of the lock-step exchange against stand-in controllers on real participants.
#include "lockstep_link.h"

#include <gtest/gtest.h>

#include "node_harness.h"
#include "teleop/transport/topics.h"

namespace teleop::twin {
namespace {

using test::eventually;
using test::test_participant_config;

constexpr size_t kJoints = 7;

// A controller stand-in: answers on the command topic when told to (each test adds its reader
// of the twin's states when the case needs it).
struct StandInController {
  transport::Participant participant{test_participant_config("controller")};
  transport::Publication<msg::JointCommand> commands{participant, transport::topics::kLockstepCommand, "controller"};

  void answer() { commands.publish(); }
};

// Exchanges until the link answers `wanted`; false after `timeout`.
bool exchange_until(LockstepLink& link, LockstepLink::Result wanted, std::chrono::milliseconds timeout) {
  return eventually([&] { return link.exchange() == wanted; }, timeout);
}

// A reader of the twin's state (an observer, a recorder) can match before the controller does:
// the twin counts as connected, and its first state reaches only that reader. Without the repeat
// of step 1 the controller never saw it and the twin reported a stall after 5 s.
TEST(LockstepLink, TheFirstStateReachesAControllerWhoseReaderMatchedAfterAnObserver) {
  transport::Participant twin_participant{test_participant_config("twin")};
  LockstepLink link(twin_participant, "twin", kJoints, 0.3, 0.001);
  transport::Participant observer_participant{test_participant_config("observer")};
  transport::Subscription<msg::JointState> observer(observer_participant, transport::topics::kLockstepState);
  StandInController controller;
  ASSERT_TRUE(eventually([&] { return link.connected(); })) << "the observer's reader and the controller's writer";
  ASSERT_EQ(link.exchange(), LockstepLink::Result::kPending);  // step 1 goes out, to the observer only
  ASSERT_TRUE(eventually([&] { return observer.poll() > 0; })) << "the observer has step 1";

  // the controller's reader joins now
  transport::Subscription<msg::JointState> controller_states(controller.participant, transport::topics::kLockstepState);
  ASSERT_TRUE(eventually([&] {
    (void)link.exchange();
    return controller_states.poll() > 0;
  })) << "step 1 never reached the late controller";
  EXPECT_EQ(controller_states.latest().header().seq(), 1u) << "the repeat keeps the step's number";
  EXPECT_GE(link.first_step_resends(), 1u);

  controller.answer();
  ASSERT_TRUE(exchange_until(link, LockstepLink::Result::kCommand, std::chrono::seconds(5)));
  EXPECT_EQ(link.steps(), 1u);
}

// Once the first command came, steps are not repeated: the reliable writer delivers them, and
// a silent controller is a stall after the timeout, not a stream of repeats.
TEST(LockstepLink, RepeatsOnlyTheFirstStepAndReportsAStallAfterTheTimeout) {
  transport::Participant twin_participant{test_participant_config("twin")};
  LockstepLink link(twin_participant, "twin", kJoints, 0.3, 0.001);
  StandInController controller;
  transport::Subscription<msg::JointState> controller_states(controller.participant, transport::topics::kLockstepState);
  ASSERT_TRUE(eventually([&] { return link.connected() && controller.commands.matched() > 0; }));
  ASSERT_TRUE(eventually([&] {
    (void)link.exchange();
    return controller_states.poll() > 0;
  }));
  controller.answer();
  ASSERT_TRUE(exchange_until(link, LockstepLink::Result::kCommand, std::chrono::seconds(5)));
  const uint64_t resends = link.first_step_resends();

  // step 2 is never answered: kStalled within the 0.3 s timeout (bounded here by 5 s, a hang check)
  ASSERT_TRUE(exchange_until(link, LockstepLink::Result::kStalled, std::chrono::seconds(5)));
  EXPECT_EQ(link.first_step_resends(), resends) << "step 2 was repeated";
  EXPECT_EQ(link.steps(), 1u);
  EXPECT_EQ(link.state_publication().sent(), 2u) << "steps 1 and 2, each published once";
}

}  // namespace
}  // namespace teleop::twin
