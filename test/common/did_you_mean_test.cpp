#include "teleop/common/did_you_mean.h"

#include <gtest/gtest.h>

namespace teleop {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("joints", "joints"), 0u);
  EXPECT_EQ(edit_distance("jionts", "joints"), 1u);  // a swap of neighbours is one typo
  EXPECT_EQ(edit_distance("lauch", "launch"), 1u);
  EXPECT_EQ(edit_distance("launchh", "launch"), 1u);
  EXPECT_EQ(edit_distance("lunch", "launch"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("record", "replay"), 4u);
}

TEST(ClosestName, SuggestsANearNameAndNothingForAFarOne) {
  const std::vector<std::string> commands{"launch", "sweep", "experiment", "record", "replay", "reset"};
  EXPECT_EQ(closest_name("lauch", commands), "launch");
  EXPECT_EQ(closest_name("experimnet", commands), "experiment");
  EXPECT_EQ(closest_name("recrod", commands), "record");
  EXPECT_EQ(closest_name("deploy", commands), std::nullopt);
  // a short word is not a typo of everything two edits away
  EXPECT_EQ(closest_name("x", commands), std::nullopt);
  EXPECT_EQ(closest_name("ab", {"an"}), std::nullopt);
}

TEST(ClosestName, PrefersTheNearestAndOnATieTheFirst) {
  EXPECT_EQ(closest_name("rate_hzz", {"rate", "rate_hz"}), "rate_hz");
  EXPECT_EQ(closest_name("reset", {"reset", "resets"}), "reset");
  EXPECT_EQ(closest_name("resex", {"reset", "resel"}), "reset");
}

TEST(DidYouMean, FormatsAHintToAppendOrNothing) {
  EXPECT_EQ(did_you_mean("jionts", {"joints"}), " (did you mean 'joints'?)");
  EXPECT_EQ(did_you_mean("nothing_like_it", {"joints"}), "");
}

}  // namespace
}  // namespace teleop
