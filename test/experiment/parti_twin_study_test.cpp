// PARTI §3.2 (teleop fidelity-study parti_twin, docs/fidelity.md) on a short taught trajectory:
// a fast swing, down onto the table, a press held, lift off; one perturbed robot. The phases are
// found, the twin follows, and the estimators behave as PARTI describes: the momentum observer
// right in free motion and in contact, eq. 5 without its inertia off in free motion and right in
// static contact, eq. 5 fed the control law's own torque blind to the contact.
#include "teleop/experiment/parti_twin_study.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace teleop::experiment {
namespace {

PartiTwinConfig short_study() {
  PartiTwinConfig c = load_parti_twin_study(std::string(TELEOP_SOURCE_DIR) + "/config/experiments/parti_twin.yaml");
  c.start_hold_s = 0.4;
  c.waypoints = {{"swing_out", {0.35, 0.30, 0.40}, 0.6, 0.1},
                 {"above_table", {0.50, 0.0, 0.08}, 0.6, 0.2},
                 {"press", {0.50, 0.0, -0.05}, 0.6, 0.8},
                 {"lift_off", {0.50, 0.0, 0.10}, 0.5, 0.2}};
  return c;
}

class PartiTwinStudy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { run_ = new PartiTwinRun(run_parti_twin_case(short_study(), 1)); }
  static void TearDownTestSuite() {
    delete run_;
    run_ = nullptr;
  }
  static const PartiTwinRun& run() { return *run_; }

 private:
  static PartiTwinRun* run_;
};
PartiTwinRun* PartiTwinStudy::run_ = nullptr;

TEST_F(PartiTwinStudy, FindsFreeMotionContactAndStaticContact) {
  const PartiTwinRun& r = run();
  EXPECT_EQ(r.mujoco_warnings, 0);
  EXPECT_GT(r.position[kFree].samples, 1500u);
  EXPECT_GT(r.position[kStaticContact].samples, 300u) << "the press held";
  EXPECT_GE(r.position[kContact].samples, r.position[kStaticContact].samples) << "static contact is contact";
  EXPECT_GT(r.static_force_n, 8.0) << "N: 3 cm below the surface at 500 N/m";
  EXPECT_LT(r.static_force_n, 25.0);
  EXPECT_GT(r.peak_force_n, r.static_force_n) << "the touchdown's impact";
}

TEST_F(PartiTwinStudy, TwinFollowsTheRealRobot) {
  const PartiTwinRun& r = run();
  std::printf("twin vs real: position mean free %.2f mm, static contact %.2f mm; force error static %.2f N\n",
              r.position[kFree].mean, r.position[kStaticContact].mean, r.force[kStaticContact].mean);
  EXPECT_LT(r.position[kFree].max, 20.0) << "mm";
  EXPECT_LT(r.force[kStaticContact].mean, 0.5 * r.static_force_n) << "the twin presses about as hard";
}

TEST_F(PartiTwinStudy, EstimatorsBehaveAsPartiDescribes) {
  const PartiTwinRun& r = run();
  const auto& e = r.estimator;
  std::printf("free max / static mean [N]: observer %.2f / %.2f, eq. 5 (g - tau_J) %.2f / %.2f, "
              "eq. 5 (command) %.2f / %.2f, direct with M ddq %.2f / %.2f\n",
              e[kObserver][kFree].max, e[kObserver][kStaticContact].mean, e[kPartiLink][kFree].max,
              e[kPartiLink][kStaticContact].mean, e[kPartiCommand][kFree].max, e[kPartiCommand][kStaticContact].mean,
              e[kDirectInertial][kFree].max, e[kDirectInertial][kStaticContact].mean);
  // in free motion eq. 5 without inertia reads the arm's own M ddq + C dq as an external force
  EXPECT_GT(e[kPartiLink][kFree].max, 3.0 * e[kObserver][kFree].max);
  // in static contact both see the contact force
  EXPECT_LT(e[kObserver][kStaticContact].mean, 0.5 * r.static_force_n);
  EXPECT_LT(e[kPartiLink][kStaticContact].mean, 0.5 * r.static_force_n);
  // fed the control law's own torque, eq. 5 only reads the drive's friction: blind to the contact
  EXPECT_GT(e[kPartiCommand][kStaticContact].mean, 0.8 * r.static_force_n);
}

TEST_F(PartiTwinStudy, ReportsPartisQualitativeResultBesideOurs) {
  const std::string md = format_parti_twin_markdown(short_study(), {run()});
  EXPECT_NE(md.find("momentum observer"), std::string::npos);
  EXPECT_NE(md.find("overestimated in free motion"), std::string::npos);
  EXPECT_NE(md.find("| static_contact |"), std::string::npos) << md;
}

}  // namespace
}  // namespace teleop::experiment
