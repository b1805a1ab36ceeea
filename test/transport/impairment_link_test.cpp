// Impairment over real Fast DDS between two processes: the publisher's egress is impaired.
// Statistical checks use 4 standard errors; nothing is timed.
#include <gtest/gtest.h>

#include <cmath>

#include "process_helpers.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

struct LinkRun {
  runtime::NodeReport pub;
  runtime::NodeReport sub;
};

// runs a publisher and a subscriber to completion and returns their reports
LinkRun run_link(const std::vector<std::string>& pub_args, const std::vector<std::string>& sub_args) {
  const std::string dir = make_temp_dir();
  const std::string domain = std::to_string(unique_domain());
  std::vector<std::string> sub = {bin("teleop_link_probe"), "--role", "sub", "--name", "receiver", "--domain", domain,
                                  "--report", dir + "/sub.yaml"};
  std::vector<std::string> pub = {bin("teleop_link_probe"), "--role", "pub", "--name", "sender", "--domain", domain,
                                  "--report", dir + "/pub.yaml"};
  sub.insert(sub.end(), sub_args.begin(), sub_args.end());
  pub.insert(pub.end(), pub_args.begin(), pub_args.end());
  RunningProcess subscriber(sub);
  const ProcessResult p = run_process(pub, std::chrono::seconds(120));
  EXPECT_EQ(p.exit_status, 0) << p.output;
  const auto s = subscriber.stop(0, std::chrono::seconds(60));  // signal 0: just wait for it
  EXPECT_EQ(s, 0) << subscriber.output();
  return {runtime::read_report(dir + "/pub.yaml"), runtime::read_report(dir + "/sub.yaml")};
}

std::string write_profile(const std::string& yaml) {
  const std::string path = make_temp_dir() + "/profile.yaml";
  write_file(path, yaml);
  return path;
}

double counter(const runtime::NodeReport& r, const std::string& name) {
  for (const auto& [n, v] : r.counters) {
    if (n == name) return v;
  }
  return -1;
}

// An outage of `samples` cycles leaves a sequence gap of that length, less the cycles the
// sender's loop skipped (stalled) and so never published; 2 % slack for the outage's edges.
void expect_gap_of_outage(uint64_t gap, double samples, double skipped) {
  ASSERT_GE(skipped, 0.0) << "the publisher reports skipped_cycles";
  const double slack = 0.02 * samples;
  EXPECT_LE(static_cast<double>(gap), samples + slack);
  EXPECT_GE(static_cast<double>(gap), samples - slack - skipped) << skipped << " cycles skipped";
}

TEST(ImpairedLink, BestEffortStreamLosesTheConfiguredFraction) {
  constexpr int kSamples = 4000;
  // discovery unimpaired: the stream starts from a matched state on both sides (with discovery
  // impaired too, the reader may learn of the writer a second after the writer learnt of it)
  const LinkRun run = run_link({"--count", std::to_string(kSamples), "--profile", source("config/network/lossy-20.yaml"),
                                "--seed", "11", "--exclude-discovery"},
                               {"--count", std::to_string(kSamples), "--duration", "30", "--idle-exit"});
  ASSERT_EQ(run.sub.received.size(), 1u);
  const auto& rx = run.sub.received[0];
  ASSERT_GT(rx.expected, 0.9 * kSamples);
  const double loss = static_cast<double>(rx.lost) / static_cast<double>(rx.expected);
  const double se = std::sqrt(0.2 * 0.8 / static_cast<double>(rx.expected));
  EXPECT_NEAR(loss, 0.2, 4 * se) << rx.lost << " of " << rx.expected;
  ASSERT_EQ(run.pub.links.size(), 1u);
  EXPECT_GT(run.pub.links[0].lost, 0u);
}

TEST(ImpairedLink, ReliableTopicDeliversEverythingDespite20PercentLoss) {
  constexpr int kSamples = 1000;
  const LinkRun run = run_link({"--qos", "event", "--rate-hz", "200", "--count", std::to_string(kSamples), "--linger", "3",
                                "--profile", source("config/network/lossy-20.yaml"), "--seed", "12"},
                               {"--qos", "event", "--count", std::to_string(kSamples), "--duration", "60"});
  const auto& rx = run.sub.received.at(0);
  EXPECT_EQ(rx.received, static_cast<uint64_t>(kSamples));
  EXPECT_EQ(rx.first_seq, 1u);
  EXPECT_EQ(rx.last_seq, static_cast<uint64_t>(kSamples));
  EXPECT_EQ(rx.lost, 0u);
  // and the link really dropped messages, which the reliability protocol repaired
  EXPECT_GT(run.pub.links.at(0).lost, 100u);
}

TEST(ImpairedLink, OutageLeavesAGapOfItsLengthInTheSequenceNumbers) {
  const std::string profile = write_profile(
      "profile:\n  name: outage-1s\n  outages: [{start_s: 2, duration_s: 1}]\n");
  constexpr int kSamples = 4000;  // 4 s at 1 kHz: the outage lies inside
  const LinkRun run = run_link({"--count", std::to_string(kSamples), "--profile", profile},
                               {"--count", std::to_string(kSamples), "--duration", "30"});
  const auto& rx = run.sub.received.at(0);
  // 1 s at 1 kHz; the sender's loop keeps its rate on absolute deadlines, but a stall of this
  // shared VM drops deadlines, and a sample never sent leaves no gap
  expect_gap_of_outage(rx.gap_max, 1000.0, counter(run.pub, "skipped_cycles"));
  EXPECT_NEAR(static_cast<double>(rx.lost), static_cast<double>(rx.gap_max), 30.0) << "little else was lost";
  EXPECT_GT(run.pub.links.at(0).outage, 900u);
}

TEST(ImpairedLink, LivelinessExpiresDuringALongOutageAndRecoversAfterIt) {
  const std::string profile = write_profile(
      "profile:\n  name: outage-3s\n  outages: [{start_s: 2, duration_s: 3}]\n");
  constexpr int kSamples = 7000;  // 7 s at 1 kHz
  const LinkRun run = run_link({"--count", std::to_string(kSamples), "--profile", profile, "--lease-ms", "500"},
                               {"--count", std::to_string(kSamples), "--duration", "40", "--lease-ms", "500"});
  const auto& rx = run.sub.received.at(0);
  EXPECT_GE(rx.liveliness_lost, 1u) << "a 3 s silence exceeds the 500 ms lease";
  EXPECT_EQ(counter(run.sub, "alive_writers_at_end"), 1.0) << "the writer is alive again after the outage";
  EXPECT_EQ(rx.last_seq, static_cast<uint64_t>(kSamples)) << "samples flow again";
  expect_gap_of_outage(rx.gap_max, 3000.0, counter(run.pub, "skipped_cycles"));
}

TEST(ImpairedLink, DiscoveryFilterLetsPeersMatchWhileAllUserDataIsLost) {
  const std::string profile = write_profile(
      "profile:\n  name: black-hole\n  loss: {model: bernoulli, probability: 1.0}\n");
  // the publisher only starts once matched: it would fail after 20 s if discovery were lost
  const LinkRun run = run_link({"--count", "500", "--profile", profile, "--exclude-discovery"},
                               {"--count", "500", "--duration", "3"});
  EXPECT_EQ(run.pub.published.at(0).sent, 500u);
  EXPECT_EQ(run.sub.received.at(0).received, 0u);
  EXPECT_GE(run.pub.links.at(0).lost, 500u);
}

}  // namespace
}  // namespace teleop::test
