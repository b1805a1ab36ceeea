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

// A reader that polls every millisecond, as a node's loop does: admit() polls (empty) up to `t`,
// then takes the one sample in a poll of its own. A candidate that takes over at the end of the
// poll reads as kNewSession, one that does not as kOtherWriter.
struct PolledSession {
  explicit PolledSession(StreamSessionPolicy policy = {}) : session(policy) {}

  Admission admit(const WriterId& w, uint64_t seq, int64_t t) {
    while (now + kMs < t) poll_empty(now + kMs);
    now = t;
    session.begin_poll(t);
    const Admission a = session.admit(w, seq, t);
    if (session.end_poll()) return Admission::kNewSession;
    return a == Admission::kCandidate ? Admission::kOtherWriter : a;
  }
  void poll_empty(int64_t t) {
    now = t;
    session.begin_poll(t);
    (void)session.end_poll();
  }
  StreamSession* operator->() { return &session; }

  StreamSession session;
  int64_t now = 0;
};

TEST(StreamSession, OpensTheFirstSessionWithTheFirstSample) {
  PolledSession s;
  EXPECT_EQ(s->session(), 0u);
  EXPECT_EQ(s.admit(writer(1), 7, 0), Admission::kNewSession);
  EXPECT_EQ(s->session(), 1u);
  EXPECT_EQ(s.admit(writer(1), 8, kMs), Admission::kNewest);
  EXPECT_EQ(s.admit(writer(1), 8, 2 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 5, 3 * kMs), Admission::kOlder);
  EXPECT_EQ(s->session(), 1u);
}

TEST(StreamSession, FollowsARestartedWriterFromItsFirstSample) {
  PolledSession s;  // takeover after 100 ms of silence
  for (uint64_t seq = 1; seq <= 8000; ++seq) ASSERT_TRUE(is_newest(s.admit(writer(1), seq, static_cast<int64_t>(seq) * kMs)));
  // the writer was killed; its successor numbers from 1 again, 2 s later
  const int64_t restart = 10'000 * kMs;
  EXPECT_EQ(s.admit(writer(2), 1, restart), Admission::kNewSession);
  EXPECT_EQ(s->session(), 2u);
  EXPECT_EQ(s.admit(writer(2), 2, restart + kMs), Admission::kNewest);
  EXPECT_EQ(s->refused_other_writer(), 0u);
}

TEST(StreamSession, RefusesAnotherWriterWhileTheFollowedOneTalks) {
  PolledSession s;
  int64_t now = 0;
  for (uint64_t seq = 1; seq <= 10; ++seq) ASSERT_TRUE(is_newest(s.admit(writer(1), seq, now += kMs)));
  // a forged sample with the largest sequence number, from another writer
  EXPECT_EQ(s.admit(writer(9), std::numeric_limits<uint64_t>::max() - 1, now += kMs), Admission::kOtherWriter);
  // the followed writer goes on as before
  EXPECT_EQ(s.admit(writer(1), 11, now += kMs), Admission::kNewest);
  EXPECT_EQ(s->refused_other_writer(), 1u);
  EXPECT_EQ(s->session(), 1u);
}

TEST(StreamSession, LetsAnotherWriterTakeOverOnlyAfterTheSilence) {
  PolledSession s(StreamSessionPolicy{20 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(2), 1, 19 * kMs), Admission::kOtherWriter);
  EXPECT_EQ(s.admit(writer(2), 2, 20 * kMs), Admission::kNewSession);
  // now the first one is the stranger
  EXPECT_EQ(s.admit(writer(1), 2, 21 * kMs), Admission::kOtherWriter);
}

TEST(StreamSession, RefusesALeapOfTheSequenceNumberFromALiveWriter) {
  PolledSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 1002, kMs), Admission::kSequenceJump);
  EXPECT_EQ(s.admit(writer(1), 1001, 2 * kMs), Admission::kNewest);  // a gap within the bound is loss
  EXPECT_EQ(s->refused_sequence_jump(), 1u);
}

TEST(StreamSession, TakesALeapAfterASilenceAsLoss) {
  // a writer cut off for minutes comes back far ahead: the samples in between were lost
  PolledSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 600'000, 600'000 * kMs), Admission::kNewest);
  EXPECT_EQ(s->session(), 1u);
}

TEST(StreamSession, NoSequenceNumberHoldsTheStreamLongerThanTheSilence) {
  // the same writer's numbers forged high after a silence: its real, lower numbers are older at
  // first, and open a new session once the forged one is as old as the takeover silence
  PolledSession s(StreamSessionPolicy{20 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 5, 0), Admission::kNewSession);
  ASSERT_EQ(s.admit(writer(1), std::numeric_limits<uint64_t>::max() - 1, 50 * kMs), Admission::kNewest);
  EXPECT_EQ(s.admit(writer(1), 6, 51 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 7, 70 * kMs), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 8, 71 * kMs), Admission::kNewest);
}

TEST(StreamSession, ARepeatOfTheNewestIsNeverANewSession) {
  // lock-step resends its first state with the same number every 100 ms until answered
  PolledSession s(StreamSessionPolicy{100 * kMs, 1000});
  ASSERT_EQ(s.admit(writer(1), 1, 0), Admission::kNewSession);
  EXPECT_EQ(s.admit(writer(1), 1, 100 * kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(1), 1, 300 * kMs), Admission::kOlder);
  EXPECT_EQ(s->session(), 1u);
}

// a stalled reader's backlog: the other writer's sample came out first, the followed writer's
// later in the same poll; the followed writer is not gone
TEST(StreamSession, AStalledReadersBacklogDoesNotHandTheStreamOver) {
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  s.begin_poll(kMs);
  ASSERT_EQ(s.admit(writer(1), 1, kMs), Admission::kNewSession);
  ASSERT_FALSE(s.end_poll());
  // the reader stops for 50 ms; both writers kept writing, everything arrives at once after
  const int64_t resumed = 51 * kMs;
  s.begin_poll(resumed);
  EXPECT_EQ(s.admit(writer(2), 40, resumed), Admission::kOtherWriter);
  EXPECT_EQ(s.admit(writer(1), 2, resumed), Admission::kNewest);
  EXPECT_EQ(s.admit(writer(2), 41, resumed), Admission::kOtherWriter);
  EXPECT_FALSE(s.end_poll());
  EXPECT_EQ(s.session(), 1u);
  EXPECT_EQ(s.refused_other_writer(), 2u);
}

// the followed writer's backlog reaches the reader a poll later than the other writer's: a
// reader that was not listening does not count that time as the followed writer's silence
TEST(StreamSession, TimeNotListeningIsNotSilence) {
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  s.begin_poll(kMs);
  ASSERT_EQ(s.admit(writer(1), 1, kMs), Admission::kNewSession);
  ASSERT_FALSE(s.end_poll());
  int64_t t = 51 * kMs;  // after a 50 ms stall: only the other writer's sample so far
  s.begin_poll(t);
  EXPECT_EQ(s.admit(writer(2), 40, t), Admission::kOtherWriter);
  EXPECT_FALSE(s.end_poll());
  t += kMs;
  s.begin_poll(t);
  EXPECT_EQ(s.admit(writer(1), 2, t), Admission::kNewest);
  EXPECT_FALSE(s.end_poll());
  EXPECT_EQ(s.session(), 1u);
}

// ... but a followed writer that is really gone is replaced once it has been silent for the
// takeover silence while we listened
TEST(StreamSession, AWriterGoneWhileWeListenIsReplacedAfterTheSilence) {
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  s.begin_poll(kMs);
  ASSERT_EQ(s.admit(writer(1), 1, kMs), Admission::kNewSession);
  ASSERT_FALSE(s.end_poll());
  int64_t t = 51 * kMs;  // a stall, then the other writer every ms and the followed one never
  uint64_t seq = 40;
  for (; t < 71 * kMs; t += kMs) {
    s.begin_poll(t);
    ASSERT_EQ(s.admit(writer(2), seq++, t), Admission::kOtherWriter) << t / kMs;
    ASSERT_FALSE(s.end_poll());
  }
  s.begin_poll(t);
  EXPECT_EQ(s.admit(writer(2), seq, t), Admission::kCandidate);
  EXPECT_TRUE(s.end_poll());
  EXPECT_EQ(s.session(), 2u);
  EXPECT_EQ(s.writer(), writer(2));
}

// two writers heard after the followed one went quiet: the first one heard takes over, with its
// newest sample of the poll; the other's are refused
TEST(StreamSession, OneCandidatePerPollTakesOverWithItsNewestSample) {
  StreamSession s(StreamSessionPolicy{20 * kMs, 1000});
  s.begin_poll(kMs);
  ASSERT_EQ(s.admit(writer(1), 1, kMs), Admission::kNewSession);
  ASSERT_FALSE(s.end_poll());
  for (int64_t t = 2 * kMs; t < 40 * kMs; t += kMs) {
    s.begin_poll(t);
    ASSERT_FALSE(s.end_poll());
  }
  const int64_t t = 40 * kMs;
  s.begin_poll(t);
  EXPECT_EQ(s.admit(writer(2), 7, t - 2), Admission::kCandidate);
  EXPECT_EQ(s.admit(writer(3), 9, t - 1), Admission::kOtherWriter);
  EXPECT_EQ(s.admit(writer(2), 8, t), Admission::kCandidate);
  EXPECT_TRUE(s.end_poll());
  EXPECT_EQ(s.writer(), writer(2));
  EXPECT_EQ(s.refused_other_writer(), 1u);
  // its next sample continues the session from the newest it took over with
  s.begin_poll(t + kMs);
  EXPECT_EQ(s.admit(writer(2), 8, t + kMs), Admission::kOlder);
  EXPECT_EQ(s.admit(writer(2), 9, t + kMs), Admission::kNewest);
  EXPECT_FALSE(s.end_poll());
}

}  // namespace
}  // namespace teleop
