#include "teleop/common/stream_session.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace teleop {
namespace {

constexpr int64_t kMs = 1'000'000;

WriterId writer(uint8_t id) {
  WriterId w;
  w.bytes.fill(id);
  return w;
}

TEST(StreamSession, OpensTheFirstSessionWithTheFirstSample) {
  StreamSession s;
  EXPECT_EQ(s.session(), 0u);
  EXPECT_EQ(s.admit(writer(1), 7, 0), Admission::kNewSession);
  EXPECT_EQ(s.session(), 1u);
  EXPECT_EQ(s.admit(writer(1), 8, kMs), Admission::kNewest);
  EXPECT_EQ(s.admit(writer(1), 8, 2 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 5, 3 * kMs), Admission::kOlder);
  EXPECT_EQ(s.session(), 1u);
}

TEST(StreamSession, FollowsARestartedWriterFromItsFirstSample) {
  StreamSession s;  // takeover after 100 ms of silence
  for (uint64_t seq = 1; seq <= 8000; ++seq) ASSERT_TRUE(is_newest(s.admit(writer(1), seq, static_cast<int64_t>(seq) * kMs)));
  // the writer was killed; its successor numbers from 1 again, 2 s later
  const int64_t restart = 10'000 * kMs;
  EXPECT_EQ(s.admit(writer(2), 1, restart), Admission::kNewSession);
  EXPECT_EQ(s.session(), 2u);
  EXPECT_EQ(s.admit(writer(2), 2, restart + kMs), Admission::kNewest);
  EXPECT_EQ(s.refused_other_writer(), 0u);
}

TEST(StreamSession, RefusesAnotherWriterWhileTheFollowedOneTalks) {
  StreamSession s;
  int64_t now = 0;
  for (uint64_t seq = 1; seq <= 10; ++seq) ASSERT_TRUE(is_newest(s.admit(writer(1), seq, now += kMs)));
  // a forged sample with the largest sequence number, from another writer
  EXPECT_EQ(s.admit(writer(9), std::numeric_limits<uint64_t>::max() - 1, now += kMs), Admission::kOtherWriter);
  // the followed writer goes on as before
  EXPECT_EQ(s.admit(writer(1), 11, now += kMs), Admission::kNewest);
  EXPECT_EQ(s.refused_other_writer(), 1u);
  EXPECT_EQ(s.session(), 1u);
}

TEST(StreamSession, LetsAnotherWriterTakeOverOnlyAfterTheSilence) {
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(2), 1, 19 * kMs), Admission::kOtherWriter);
  EXPECT_EQ(s.admit(writer(2), 2, 20 * kMs), Admission::kNewSession);
  // now the first one is the stranger
  EXPECT_EQ(s.admit(writer(1), 2, 21 * kMs), Admission::kOtherWriter);
}

TEST(StreamSession, RefusesALeapOfTheSequenceNumberFromALiveWriter) {
  StreamSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 1002, kMs), Admission::kSequenceJump);
  EXPECT_EQ(s.admit(writer(1), 1001, 2 * kMs), Admission::kNewest);  // a gap within the bound is loss
  EXPECT_EQ(s.refused_sequence_jump(), 1u);
}

TEST(StreamSession, TakesALeapAfterASilenceAsLoss) {
  // a writer cut off for minutes comes back far ahead: the samples in between were lost
  StreamSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 600'000, 600'000 * kMs), Admission::kNewest);
  EXPECT_EQ(s.session(), 1u);
}

TEST(StreamSession, NoSequenceNumberHoldsTheStreamLongerThanTheSilence) {
  // the same writer's numbers forged high after a silence: its real, lower numbers are older at
  // first, and open a new session once the forged one is as old as the takeover silence
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 5, 0), Admission::kNewSession);
  ASSERT_EQ(s.admit(writer(1), std::numeric_limits<uint64_t>::max() - 1, 50 * kMs), Admission::kNewest);
  EXPECT_EQ(s.admit(writer(1), 6, 51 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 7, 70 * kMs), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 8, 71 * kMs), Admission::kNewest);
}

TEST(StreamSession, ARepeatOfTheNewestIsNeverANewSession) {
  // lock-step resends its first state with the same number every 100 ms until answered
  StreamSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 1, 100 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 1, 300 * kMs), Admission::kOlder);
  EXPECT_EQ(s.session(), 1u);
}

}  // namespace
}  // namespace teleop
