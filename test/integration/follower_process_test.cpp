// The follower as a real process driven by a real leader process over DDS: tracking of a scripted
// joint-impedance motion (thesis §4.1 metrics), and the watchdog when the leader is killed.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <mutex>
#include <thread>

#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"

namespace teleop::test {
namespace {

struct Pair {
  std::string dir = make_temp_dir();
  int domain = unique_domain();
  std::vector<std::string> args(const std::string& node, const std::string& config) const {
    return {bin("teleop_" + node), "--config", config, "--domain", std::to_string(domain), "--report", dir + "/" + node + ".yaml"};
  }
  // the shipped leader, but moving joints that swing the flange along the wall, not into it
  std::string leader_clear_of_the_wall() const {
    return config_copy(dir, "leader.yaml",
                       {{"amplitudes_rad: [0.0, 0.2, 0.0, 0.2, 0.0, 0.0, 0.0]", "amplitudes_rad: [0.3, 0.0, 0.0, 0.0, 0.3, 0.0, 0.3]"}});
  }
  // the shipped follower with a command timeout longer than the leader's liveliness lease
  std::string follower_with_long_timeout() const {
    return config_copy(dir, "follower.yaml", {{"command_timeout_ms: 20", "command_timeout_ms: 5000"}});
  }
};

// The follower's JointState samples as the test sees them on the bus (same host: the monotonic
// stamps compare with this process's clock).
class StateRecorder {
 public:
  struct Sample {
    uint64_t seq;  // the follower publishes its state once per cycle: seq counts its cycles
    int64_t mono_ns;
    std::array<double, 7> q;
    std::array<double, 7> tau;
  };
  explicit StateRecorder(int domain) : participant_(bus_participant(domain, "recorder")), sub_(participant_, transport::topics::kFollowerState) {
    thread_ = std::thread([this] {
      while (!stop_) {
        while (sub_.poll() > 0) {
        }
        record();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  }
  ~StateRecorder() {
    stop_ = true;
    thread_.join();
  }
  std::vector<Sample> samples() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }

 private:
  void record() {
    if (!sub_.has_sample() || sub_.latest().header().seq() == last_seq_) return;
    const auto& s = sub_.latest();
    last_seq_ = s.header().seq();
    if (s.q_rad().size() != 7 || s.tau_measured_nm().size() != 7) return;
    Sample out{s.header().seq(), s.header().stamp_mono_ns(), {}, {}};
    std::copy_n(s.q_rad().begin(), 7, out.q.begin());
    std::copy_n(s.tau_measured_nm().begin(), 7, out.tau.begin());
    std::lock_guard<std::mutex> lock(mutex_);
    samples_.push_back(out);
  }

  transport::Participant participant_;
  transport::Subscription<msg::JointState> sub_;
  uint64_t last_seq_ = 0;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<Sample> samples_;
  std::thread thread_;
};

TEST(FollowerProcess, TracksTheLeadersScriptedJointImpedanceMotion) {
  Pair pair;
  RunningProcess follower(pair.args("follower", source("config/nodes/follower.yaml")));
  RunningProcess leader(pair.args("leader", pair.leader_clear_of_the_wall()));
  ASSERT_TRUE(follower.wait_for_output("starting", std::chrono::seconds(20))) << follower.output();
  follower.run_for(std::chrono::milliseconds(4000));  // two periods of the 0.5 Hz motion
  ASSERT_EQ(follower.stop(SIGTERM, std::chrono::seconds(10)), 0) << follower.output();
  ASSERT_EQ(leader.stop(SIGTERM, std::chrono::seconds(10)), 0) << leader.output();

  const auto report = runtime::read_report(pair.dir + "/follower.yaml");
  const double rmse = counter(report, "tracking_rmse_rad");
  const double max_error = counter(report, "tracking_max_error_rad");
  RecordProperty("tracking_rmse_rad", std::to_string(rmse));
  RecordProperty("tracking_max_error_rad", std::to_string(max_error));
  std::printf("follower tracking over DDS: RMSE %.4f rad, max %.4f rad\n", rmse, max_error);
  // K = 200 Nm/rad against 0.3 rad at 0.5 Hz: the inertial lag is a few 0.01 rad at most
  EXPECT_GT(rmse, 0.0) << "errors were measured";
  EXPECT_LT(rmse, 0.02);
  EXPECT_LT(max_error, 0.08);
  EXPECT_LT(counter(report, "peak_external_force_n"), 20.0) << "the motion stays clear of the wall";
  EXPECT_EQ(report.final_state, "running");
}

TEST(FollowerProcess, HoldsWithinTheTimeoutWithoutATorqueStepWhenTheLeaderIsKilled) {
  Pair pair;
  StateRecorder recorder(pair.domain);
  RunningProcess leader(pair.args("leader", source("config/nodes/leader.yaml")));
  RunningProcess follower(pair.args("follower", source("config/nodes/follower.yaml")));
  ASSERT_TRUE(follower.wait_for_output("starting", std::chrono::seconds(20))) << follower.output();
  follower.run_for(std::chrono::milliseconds(1500));
  const int64_t killed_ns = monotonic_now_ns();
  leader.process().signal(SIGKILL);
  follower.run_for(std::chrono::milliseconds(1000));
  ASSERT_EQ(follower.stop(SIGTERM, std::chrono::seconds(10)), 0) << follower.output();

  const auto report = runtime::read_report(pair.dir + "/follower.yaml");
  EXPECT_EQ(report.final_state, "safe_hold");
  EXPECT_EQ(counter(report, "watchdog_trips"), 1.0);
  // command_timeout_ms is 20 in follower.yaml; the watchdog counts 1 ms cycles
  const double latency_ms = counter(report, "watchdog_latency_max_ms");
  RecordProperty("watchdog_latency_ms", std::to_string(latency_ms));
  EXPECT_GE(latency_ms, 20.0);
  EXPECT_LE(latency_ms, 22.0) << "timeout + 2 cycles";
  EXPECT_LE(counter(report, "peak_torque_ratio"), 1.0);

  // from the samples on the bus: no torque step beyond the rate limit (1000 Nm/s: 1 Nm per
  // cycle; samples lost on the way or not taken by the recorder merge cycles, counted by the
  // sequence numbers, not the time stamps, which late cycles bunch up), and the pose held after the trip
  const auto samples = recorder.samples();
  ASSERT_GT(samples.size(), 1000u) << "enough cycles to judge (the sanitizer build's half rate gave 1463)";
  double largest_step = 0.0;
  for (size_t k = 1; k < samples.size(); ++k) {
    const double cycles = static_cast<double>(samples[k].seq - samples[k - 1].seq);
    for (size_t j = 0; j < 7; ++j) largest_step = std::max(largest_step, std::abs(samples[k].tau[j] - samples[k - 1].tau[j]) / cycles);
  }
  RecordProperty("largest_torque_step_nm", std::to_string(largest_step));
  EXPECT_LE(largest_step, 1.0 + 1e-6);
  const int64_t held_from = killed_ns + 200'000'000;  // well after the trip
  std::array<double, 7> first{};
  bool have_first = false;
  double drift = 0.0;
  for (const auto& s : samples) {
    if (s.mono_ns < held_from) continue;
    if (!have_first) {
      first = s.q;
      have_first = true;
    }
    for (size_t j = 0; j < 7; ++j) drift = std::max(drift, std::abs(s.q[j] - first[j]));
  }
  ASSERT_TRUE(have_first) << "samples after the trip";
  EXPECT_LT(drift, 0.01) << "the hold keeps the pose";
}

TEST(FollowerProcess, HoldsWhenTheLeadersLivelinessLapsesBeforeTheCommandTimeout) {
  Pair pair;
  const std::string config = pair.follower_with_long_timeout();
  RunningProcess leader(pair.args("leader", source("config/nodes/leader.yaml")));
  RunningProcess follower(pair.args("follower", config));
  ASSERT_TRUE(follower.wait_for_output("starting", std::chrono::seconds(20))) << follower.output();
  follower.run_for(std::chrono::milliseconds(1500));
  leader.process().signal(SIGKILL);
  // the leader's lease is 250 ms (leader.yaml); the 5 s command timeout is far away
  follower.run_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(follower.stop(SIGTERM, std::chrono::seconds(10)), 0) << follower.output();

  const auto report = runtime::read_report(pair.dir + "/follower.yaml");
  EXPECT_EQ(report.final_state, "safe_hold") << read_file(pair.dir + "/follower.yaml") << follower.output();
  EXPECT_EQ(counter(report, "liveliness_trips"), 1.0);
  const double latency_ms = counter(report, "watchdog_latency_max_ms");
  RecordProperty("liveliness_hold_latency_ms", std::to_string(latency_ms));
  EXPECT_LT(latency_ms, 1500.0) << "the lease, not the 5 s timeout, ended the commands";
}

}  // namespace
}  // namespace teleop::test
