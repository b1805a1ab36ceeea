// `teleop record --topics`: which names a recording can ask for.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/tools/recorder.h"
#include "teleop/transport/topics.h"
#include "test_helpers.h"

namespace teleop::tools {
namespace {

TEST(RecordTopics, FixedNamesAndMembersOfAFamilyAreTeleopTopics) {
  EXPECT_NO_THROW(check_record_topics({}));
  EXPECT_NO_THROW(check_record_topics(std::vector<std::string>{transport::topics::kLeaderCommand.name, transport::topics::kFollowerState.name}));
  EXPECT_NO_THROW(check_record_topics({std::string(transport::topics::kTwinContactWrenchPrefix) + "finger_table"}));
  EXPECT_NO_THROW(check_record_topics({std::string(transport::topics::kFollowerObjectPosePrefix) + "box"}));
}

TEST(RecordTopics, ATypoIsRefusedNamingTheTopicItMayHaveMeant) {
  EXPECT_EQ(test::error_of<ConfigError>([] { check_record_topics({"teleop/leader/joint_comand"}); }),
            "--topics teleop/leader/joint_comand: not a teleop topic (did you mean 'teleop/leader/joint_command'?) "
            "(`teleop topic list` shows the bus's topics)");
}

TEST(RecordTopics, AFamilysPrefixAloneIsNoTopic) {
  const std::string error =
      test::error_of<ConfigError>([] { check_record_topics(std::vector<std::string>{transport::topics::kTwinContactWrenchPrefix}); });
  EXPECT_NE(error.find("not a teleop topic"), std::string::npos) << error;
}

}  // namespace
}  // namespace teleop::tools
