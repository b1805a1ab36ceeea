// Drift compensation of the follower's TDPA port (control/drift_compensation.h, docs/tdpa.md).
#include "teleop/control/drift_compensation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "tdpa_test_loop.h"

namespace teleop::control {
namespace {

DriftCompensationConfig config(double tau_s, double max_speed) {
  DriftCompensationConfig c;
  c.channels = 2;
  c.time_constant_s = tau_s;
  c.max_speed.fill(max_speed);
  return c;
}

TEST(DriftCompensator, TracksTheDriftAsTheIntegralOfWhatTheControllerTookAway) {
  DriftCompensator d(config(0.0, 1.0));
  d.account(0, 0.2, 0.15, 0.001);  // 0.05 m/s held back for a cycle
  d.account(0, 0.2, 0.15, 0.001);
  d.account(1, -0.1, 0.0, 0.001);
  EXPECT_NEAR(d.drift(0), -1e-4, 1e-15);
  EXPECT_NEAR(d.drift(1), 1e-4, 1e-15);
  // without a time constant nothing is asked back
  EXPECT_EQ(d.request(0, 0.2, 0.0), 0.2);
  d.reset();
  EXPECT_EQ(d.drift(0), 0.0);
  EXPECT_EQ(d.drift(1), 0.0);
}

TEST(DriftCompensator, AsksTheDriftBackWithItsTimeConstantUpToTheSpeedLimit) {
  DriftCompensator d(config(0.5, 0.1));
  d.account(0, 0.0, -0.02, 1.0);  // drift -0.02 m
  d.account(1, 0.0, 1.0, 1.0);    // drift +1 m
  EXPECT_NEAR(d.request(0, 0.3, 0.0), 0.3 + 0.02 / 0.5, 1e-12);
  EXPECT_NEAR(d.request(1, 0.3, 0.0), 0.3 - 0.1, 1e-12);  // 2 m/s asked, 0.1 m/s allowed
}

TEST(DriftCompensator, NeverReturnsTheDriftIntoAContact) {
  DriftCompensationConfig c = config(0.5, 0.1);
  c.contact_force = {3.0, 0.5};  // N on channel 0, N m on channel 1
  DriftCompensator d(c);
  // both references lag 2 cm behind: the return goes + (0.04 m/s)
  d.account(0, 0.0, -0.02, 1.0);
  d.account(1, 0.0, -0.02, 1.0);
  EXPECT_EQ(d.request(0, 0.3, -9.0), 0.3) << "a wall pushes back with 9 N: returning would press harder";
  EXPECT_NEAR(d.request(0, 0.3, 9.0), 0.3 + 0.04, 1e-12) << "a push along the return: it eases the contact";
  EXPECT_NEAR(d.request(0, 0.3, -2.5), 0.3 + 0.04, 1e-12) << "below the threshold: free motion";
  EXPECT_EQ(d.request(1, 0.3, -0.6), 0.3);
  EXPECT_NEAR(d.request(1, 0.3, -0.4), 0.3 + 0.04, 1e-12);
}

TEST(DriftCompensator, ReturnsTheDriftExponentiallyWhenTheControllerLetsItThrough) {
  const double tau = 0.2, h = 0.001;
  DriftCompensator d(config(tau, 10.0));
  d.account(0, 0.0, 0.05, 1.0);  // drift +0.05 m
  for (int k = 0; k < 200; ++k) {
    const double v_out = d.request(0, 0.0, 0.0);  // a controller with energy to spare passes it
    d.account(0, 0.0, v_out, h);
  }
  EXPECT_NEAR(d.drift(0), 0.05 * std::exp(-1.0), 2e-4);  // one time constant
}

TEST(DriftCompensator, RejectsBadConfigurationNamingTheField) {
  const auto message = [](const DriftCompensationConfig& c) {
    try {
      DriftCompensator d(c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(config(-1.0, 1.0)).find("time_constant_s"), std::string::npos);
  EXPECT_NE(message(config(std::numeric_limits<double>::quiet_NaN(), 1.0)).find("time_constant_s"), std::string::npos);
  EXPECT_NE(message(config(0.5, 0.0)).find("max_speed"), std::string::npos);
  auto no_contact = config(0.5, 1.0);
  no_contact.contact_force[1] = 0.0;
  EXPECT_NE(message(no_contact).find("contact_force of channel 1"), std::string::npos);
  auto none = config(0.5, 1.0);
  none.channels = 0;
  EXPECT_NE(message(none).find("channels"), std::string::npos);
}

struct DriftRun {
  test::LoopResult result;
  double min_w = 0.0;
};

DriftRun run(test::LoopParams p) {
  DriftRun r;
  r.result = test::run_loop(p, [&](const test::CycleView& c) {
    for (std::size_t j = 0; j < test::kLoopDof; ++j) {
      r.min_w = std::min({r.min_w, c.leader.observed_energy_j(j), c.follower.observed_energy_j(j)});
    }
  });
  return r;
}

void expect_compensation_keeps_passivity_and_returns_the_drift(test::LoopParams p, const char* what) {
  p.cycles = 8000;
  p.drift_time_constant_s = 0.0;
  const DriftRun plain = run(p);
  p.drift_time_constant_s = 0.5;
  const DriftRun compensated = run(p);
  std::printf(
      "%s: free-DOF tracking error over the last second, plain TDPA %.4g m, drift-compensated %.4g m "
      "(whole run %.4g / %.4g m); final drift %.4g / %.4g m; min W %.3g / %.3g J; wall DOF last-second "
      "peak-to-peak %.3g / %.3g m; follower dissipated %.4g / %.4g J\n",
      what, plain.result.late_free_tracking_error_m, compensated.result.late_free_tracking_error_m,
      plain.result.max_free_tracking_error_m, compensated.result.max_free_tracking_error_m,
      plain.result.final_drift_m[1], compensated.result.final_drift_m[1], plain.min_w, compensated.min_w,
      plain.result.late_peak_to_peak_m, compensated.result.late_peak_to_peak_m,
      plain.result.follower_dissipated_j[1], compensated.result.follower_dissipated_j[1]);
  // the compensation costs no passivity: W never below zero on either port
  EXPECT_GE(compensated.min_w, 0.0);
  EXPECT_GE(compensated.result.leader_min_observed_j, 0.0);
  EXPECT_GE(compensated.result.follower_min_observed_j, 0.0);
  // and the free DOF follows the leader again: the drift plain TDPA leaves is mostly returned
  EXPECT_GT(std::abs(plain.result.final_drift_m[1]), 0.01);
  EXPECT_LT(std::abs(compensated.result.final_drift_m[1]), 0.25 * std::abs(plain.result.final_drift_m[1]));
  EXPECT_LT(compensated.result.late_free_tracking_error_m, 0.5 * plain.result.late_free_tracking_error_m);
  // the wall DOF still comes to rest on the wall
  EXPECT_LT(compensated.result.late_peak_to_peak_m, 1e-3);
}

TEST(DriftCompensator, ReturnsTheDriftOfTdpaUnderDelayWithoutLosingPassivity) {
  expect_compensation_keeps_passivity_and_returns_the_drift(test::LoopParams{}, "50+50 cycle delay");
}

TEST(DriftCompensator, ReturnsTheDriftOfTdpaUnderLossAndJitterWithoutLosingPassivity) {
  test::LoopParams p;
  for (auto* link : {&p.leader_to_follower, &p.follower_to_leader}) {
    link->delay_cycles = 50;
    link->jitter_cycles = 10;
    link->drop = 0.2;
  }
  p.leader_to_follower.bursts = {{700, 850}, {2000, 2100}};
  p.follower_to_leader.bursts = {{1200, 1400}, {3000, 3050}};
  p.seed = 42;
  expect_compensation_keeps_passivity_and_returns_the_drift(p, "50-60 cycle delay, 20 % loss, bursts");
}

}  // namespace
}  // namespace teleop::control
