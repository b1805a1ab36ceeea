// The impairment model alone, on a virtual clock: statistics over >= 100k decisions, checked
// within their sampling error (4 standard errors), so the tests are seeded and never flaky.
#include "teleop/transport/impairment/link_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace teleop::transport::impairment {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int kN = 200'000;

LinkProfile profile_with(const LinkPhase& phase) {
  LinkProfile p;
  p.name = "test";
  p.phases = {phase};
  return p;
}

struct Moments {
  double mean = 0;
  double sd = 0;
};

// delays of kN messages spaced far apart (1 s), so that keeping order never alters a delay
Moments delay_moments(const LinkPhase& phase, uint64_t seed = 1) {
  LinkModel model(profile_with(phase), seed, 0);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kN; ++i) {
    const int64_t now = static_cast<int64_t>(i) * 1000 * kMs;
    const Decision d = model.decide(now, 300);
    const double delay = static_cast<double>(d.deliver_at_ns[0] - now);
    sum += delay;
    sum2 += delay * delay;
  }
  const double mean = sum / kN;
  return {mean, std::sqrt(sum2 / kN - mean * mean)};
}

TEST(LinkModel, SameSeedGivesTheSameDecisions) {
  LinkPhase phase;
  phase.delay_ns = 17 * kMs;
  phase.jitter_ns = 2 * kMs;
  phase.distribution = DelayDistribution::kNormal;
  phase.loss = {LossModel::kGilbertElliott, 0, 0.02, 0.3, 1.0, 0.0};
  phase.duplicate_probability = 0.01;
  LinkModel a(profile_with(phase), 42, 0), b(profile_with(phase), 42, 0), c(profile_with(phase), 43, 0);
  int differ_from_c = 0;
  for (int i = 0; i < kN; ++i) {
    const int64_t now = static_cast<int64_t>(i) * kMs;
    const Decision da = a.decide(now, 300), db = b.decide(now, 300), dc = c.decide(now, 300);
    ASSERT_EQ(da.drop, db.drop) << i;
    ASSERT_EQ(da.copies, db.copies) << i;
    ASSERT_EQ(da.deliver_at_ns, db.deliver_at_ns) << i;
    differ_from_c += da.drop != dc.drop || da.deliver_at_ns != dc.deliver_at_ns;
  }
  EXPECT_GT(differ_from_c, kN / 2) << "another seed gives other decisions";
}

TEST(LinkModel, ConstantDelayIsExact) {
  LinkPhase phase;
  phase.delay_ns = 17'500'000;
  LinkModel model(profile_with(phase), 1, 0);
  for (int i = 0; i < kN; ++i) {
    const int64_t now = static_cast<int64_t>(i) * kMs;
    ASSERT_EQ(model.decide(now, 300).deliver_at_ns[0] - now, 17'500'000) << i;
  }
}

TEST(LinkModel, UniformJitterHasTheMomentsOfAUniformDistribution) {
  LinkPhase phase;
  phase.delay_ns = 20 * kMs;
  phase.jitter_ns = 4 * kMs;
  phase.distribution = DelayDistribution::kUniform;
  const Moments m = delay_moments(phase);
  const double sd = 4e6 / std::sqrt(3.0);
  EXPECT_NEAR(m.mean, 20e6, 4 * sd / std::sqrt(kN));
  EXPECT_NEAR(m.sd, sd, 0.01 * sd);
}

TEST(LinkModel, NormalJitterHasTheConfiguredMeanAndStandardDeviation) {
  LinkPhase phase;
  phase.delay_ns = 20 * kMs;
  phase.jitter_ns = 2 * kMs;
  phase.distribution = DelayDistribution::kNormal;
  const Moments m = delay_moments(phase);
  EXPECT_NEAR(m.mean, 20e6, 4 * 2e6 / std::sqrt(kN));
  // standard error of a standard deviation: sd / sqrt(2n)
  EXPECT_NEAR(m.sd, 2e6, 4 * 2e6 / std::sqrt(2.0 * kN));
}

TEST(LinkModel, ParetoJitterHasTheConfiguredMeanAndAHeavyRightTail) {
  LinkPhase phase;
  phase.delay_ns = 30 * kMs;
  phase.jitter_ns = 3 * kMs;
  phase.distribution = DelayDistribution::kPareto;
  LinkModel model(profile_with(phase), 7, 0);
  double sum = 0;
  int above_3sd = 0, below_3sd = 0;
  for (int i = 0; i < kN; ++i) {
    const int64_t now = static_cast<int64_t>(i) * 1000 * kMs;
    const double delay = static_cast<double>(model.decide(now, 300).deliver_at_ns[0] - now);
    sum += delay;
    above_3sd += delay > 30e6 + 3 * 3e6;
    below_3sd += delay < 30e6 - 3 * 3e6;
  }
  // the mean converges slowly for shape 3 (infinite third moment): a looser, still seeded bound
  EXPECT_NEAR(sum / kN, 30e6, 0.02 * 30e6);
  EXPECT_GT(above_3sd, 100) << "heavy right tail";
  EXPECT_EQ(below_3sd, 0) << "bounded left tail (Pareto minimum at mean - 1.73 sd)";
}

TEST(LinkModel, CorrelationMakesSuccessiveDelaysAlike) {
  LinkPhase phase;
  phase.delay_ns = 20 * kMs;
  phase.jitter_ns = 4 * kMs;
  phase.distribution = DelayDistribution::kUniform;
  auto lag1 = [&](double correlation) {
    phase.correlation = correlation;
    LinkModel model(profile_with(phase), 3, 0);
    std::vector<double> d(kN);
    for (int i = 0; i < kN; ++i) {
      const int64_t now = static_cast<int64_t>(i) * 1000 * kMs;
      d[static_cast<size_t>(i)] = static_cast<double>(model.decide(now, 300).deliver_at_ns[0] - now);
    }
    double mean = 0;
    for (double x : d) mean += x / kN;
    double num = 0, den = 0;
    for (size_t i = 0; i + 1 < d.size(); ++i) num += (d[i] - mean) * (d[i + 1] - mean);
    for (double x : d) den += (x - mean) * (x - mean);
    return num / den;
  };
  EXPECT_NEAR(lag1(0.0), 0.0, 4 / std::sqrt(kN));
  EXPECT_GT(lag1(0.75), 0.5);
}

TEST(LinkModel, BernoulliLossRateMatches) {
  for (double p : {0.01, 0.05, 0.2}) {
    LinkPhase phase;
    phase.loss = {LossModel::kBernoulli, p};
    LinkModel model(profile_with(phase), 11, 0);
    for (int i = 0; i < kN; ++i) model.decide(static_cast<int64_t>(i) * kMs, 300);
    const double rate = static_cast<double>(model.stats().lost) / kN;
    EXPECT_NEAR(rate, p, 4 * std::sqrt(p * (1 - p) / kN)) << "p = " << p;
    EXPECT_EQ(model.stats().messages, static_cast<uint64_t>(kN));
  }
}

TEST(LinkModel, GilbertElliottLossRateAndBurstLengthMatch) {
  LinkPhase phase;
  // p = 1 %, r = 25 %: bursts of 4 on average, 3.85 % of messages lost
  phase.loss = {LossModel::kGilbertElliott, 0, 0.01, 0.25, 1.0, 0.0};
  LinkModel model(profile_with(phase), 5, 0);
  constexpr int kMany = 1'000'000;
  for (int i = 0; i < kMany; ++i) model.decide(static_cast<int64_t>(i) * kMs, 300);
  const double rate = static_cast<double>(model.stats().lost) / kMany;
  EXPECT_NEAR(rate, phase.loss.expected_loss_rate(), 0.05 * phase.loss.expected_loss_rate());
  // with loss only in the bad state, a run of losses is a stay in the bad state: geometric, mean 1/r
  EXPECT_NEAR(model.stats().loss_runs.mean_ns(), phase.loss.expected_bad_run_length(), 0.05 * 4.0);
}

TEST(LinkModel, KeepsOrderDespiteJitterUnlessReorderingIsAsked) {
  LinkPhase phase;
  phase.delay_ns = 20 * kMs;
  phase.jitter_ns = 5 * kMs;  // far more than the 1 ms spacing
  phase.distribution = DelayDistribution::kNormal;
  LinkModel ordered(profile_with(phase), 9, 0);
  int64_t last = 0;
  for (int i = 0; i < kN; ++i) {
    const Decision d = ordered.decide(static_cast<int64_t>(i) * kMs, 300);
    ASSERT_GE(d.deliver_at_ns[0], last) << "message " << i << " overtook the one before";
    last = d.deliver_at_ns[0];
  }
  phase.reorder_probability = 0.1;
  LinkModel reordering(profile_with(phase), 9, 0);
  int overtakes = 0;
  last = 0;
  for (int i = 0; i < kN; ++i) {
    const Decision d = reordering.decide(static_cast<int64_t>(i) * kMs, 300);
    overtakes += d.deliver_at_ns[0] < last;
    last = std::max(last, d.deliver_at_ns[0]);
  }
  EXPECT_NEAR(static_cast<double>(reordering.stats().reordered) / kN, 0.1, 4 * std::sqrt(0.09 / kN));
  EXPECT_GT(overtakes, kN / 20);
}

TEST(LinkModel, DuplicatesAtTheConfiguredRate) {
  LinkPhase phase;
  phase.duplicate_probability = 0.05;
  LinkModel model(profile_with(phase), 13, 0);
  for (int i = 0; i < kN; ++i) model.decide(static_cast<int64_t>(i) * kMs, 300);
  EXPECT_NEAR(static_cast<double>(model.stats().duplicated) / kN, 0.05, 4 * std::sqrt(0.05 * 0.95 / kN));
  EXPECT_EQ(model.stats().delivered, kN + model.stats().duplicated);
}

TEST(LinkModel, OutageDropsExactlyTheMessagesInItsWindow) {
  LinkProfile profile;
  profile.name = "outage";
  profile.outages = {{2000 * kMs, 500 * kMs}};
  LinkModel model(profile, 1, 1'000'000 * kMs);  // the link starts at an arbitrary clock value
  for (int i = 0; i < 5000; ++i) {
    const int64_t t = static_cast<int64_t>(i) * kMs;
    const Decision d = model.decide(1'000'000 * kMs + t, 300);
    const bool inside = t >= 2000 * kMs && t < 2500 * kMs;
    ASSERT_EQ(d.drop, inside ? DropReason::kOutage : DropReason::kNone) << "t = " << i << " ms";
  }
  EXPECT_EQ(model.stats().outage, 500u);
  EXPECT_EQ(model.stats().loss_runs.max_ns(), 500);
}

TEST(LinkModel, PhasesSwitchAtTheirTimes) {
  LinkProfile profile;
  profile.name = "phased";
  LinkPhase clean;
  clean.duration_ns = 1000 * kMs;
  LinkPhase slow;
  slow.delay_ns = 17 * kMs;
  slow.duration_ns = 1000 * kMs;
  LinkPhase down;
  down.down = true;
  profile.phases = {clean, slow, down};
  LinkModel model(profile, 1, 0);
  EXPECT_EQ(model.decide(999 * kMs, 10).deliver_at_ns[0], 999 * kMs);
  EXPECT_EQ(model.decide(1000 * kMs, 10).deliver_at_ns[0], 1017 * kMs);
  EXPECT_EQ(model.decide(1999 * kMs, 10).deliver_at_ns[0], 2016 * kMs);
  EXPECT_EQ(model.decide(2000 * kMs, 10).drop, DropReason::kOutage);
  EXPECT_EQ(model.decide(100'000 * kMs, 10).drop, DropReason::kOutage) << "the last phase lasts";
}

TEST(LinkModel, RateLimitSerialisesAndDropsWhenTheQueueIsFull) {
  LinkPhase phase;
  phase.rate_bps = 1e6;  // 1250 bytes take 10 ms
  phase.queue_limit = 5;
  LinkModel model(profile_with(phase), 1, 0);
  // one message every 1 ms: each waits for the ones before it
  std::vector<Decision> d;
  for (int i = 0; i < 20; ++i) d.push_back(model.decide(static_cast<int64_t>(i) * kMs, 1250));
  EXPECT_EQ(d[0].deliver_at_ns[0], 10 * kMs);
  EXPECT_EQ(d[1].deliver_at_ns[0], 20 * kMs);
  EXPECT_EQ(d[4].deliver_at_ns[0], 50 * kMs);
  EXPECT_EQ(d[5].drop, DropReason::kQueue) << "five queued, the sixth does not fit";
  EXPECT_GT(model.stats().queue, 10u);
}

TEST(LinkModel, TransparentProfileChangesNothing) {
  LinkModel model(profile_with(LinkPhase{}), 1, 0);
  EXPECT_TRUE(model.profile().is_transparent());
  for (int i = 0; i < 1000; ++i) {
    const Decision d = model.decide(static_cast<int64_t>(i) * kMs, 300);
    ASSERT_EQ(d.copies, 1);
    ASSERT_EQ(d.deliver_at_ns[0], static_cast<int64_t>(i) * kMs);
  }
}

}  // namespace
}  // namespace teleop::transport::impairment
