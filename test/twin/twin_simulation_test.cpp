// The twin's simulation: coupling (PARTI eq. 2), constraint-torque rendering (eq. 3), safety
// margin planes (§3.1), observed contact wrenches and distances.
#include "teleop/twin/twin_simulation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.h"
#include "twin_test_util.h"

namespace teleop::twin {
namespace {

using test::kShoulder;

// holds the coupled robot at the keyframe plus `offset` on the shoulder for `steps`
void hold_shoulder_offset(TwinSimulation& sim, const JointVector& home, double offset, int steps) {
  JointVector target = home;
  target[kShoulder] += offset;
  for (int k = 0; k < steps; ++k) sim.step_coupled(target);
}

TEST(TwinSimulation, TracksAScriptedCoupledMotionWithSmallError) {
  TwinModelConfig config;
  config.model_path = test::model_path("panda.xml");
  config.keyframe = "ready";
  TwinSimulation sim(config);
  const JointVector home = sim.q_rad();
  // 0.2 rad, 0.5 Hz on every joint (a slow operator motion), 3 s; error after the first second
  double worst_tracking = 0.0;
  JointVector target = home;
  for (int k = 0; k < 3000; ++k) {
    const double t = k * 1e-3;
    for (size_t i = 0; i < sim.joints(); ++i) target[i] = home[i] + 0.2 * std::sin(2 * M_PI * 0.5 * t);
    sim.step_coupled(target);
    if (t < 1.0) continue;
    for (size_t i = 0; i < sim.joints(); ++i) worst_tracking = std::max(worst_tracking, std::abs(target[i] - sim.q_rad()[i]));
  }
  // then held still: what remains is the joints' dry friction against the coupling stiffness
  for (int k = 0; k < 2000; ++k) sim.step_coupled(target);
  double worst_static = 0.0;
  for (size_t i = 0; i < sim.joints(); ++i) worst_static = std::max(worst_static, std::abs(target[i] - sim.q_rad()[i]));
  RecordProperty("tracking_error_rad", std::to_string(worst_tracking));
  RecordProperty("static_error_rad", std::to_string(worst_static));
  EXPECT_LT(worst_tracking, 0.03) << "K = 300 Nm/rad, D = 10 Nms/rad, bias forces compensated";
  EXPECT_LT(worst_static, 0.003) << "frictionloss <= 0.64 Nm over K = 300 Nm/rad is at most 2.1e-3 rad";
  for (size_t i = 0; i < sim.joints(); ++i) EXPECT_NEAR(sim.constraint_torque_nm()[i], 0.0, 1e-9) << "free space";
  EXPECT_EQ(sim.warnings(), 0);
}

TEST(TwinSimulation, RenderedTorquePointsOutOfTheWallAndGrowsWithPenetration) {
  TwinSimulation sim(test::wall_model());
  const JointVector home = sim.q_rad();
  hold_shoulder_offset(sim, home, 0.0, 300);
  EXPECT_EQ(sim.contact_count(0), 0);
  EXPECT_GT(sim.distance_m(0), 0.03) << "the flange starts 5 cm from the wall";
  double previous = 0.0;
  for (const double offset : {0.15, 0.2, 0.25}) {
    hold_shoulder_offset(sim, home, offset, 1000);
    const double tau = sim.constraint_torque_nm()[kShoulder];
    SCOPED_TRACE(offset);
    EXPECT_LT(tau, 0.0) << "pushes the shoulder back, out of the wall";
    EXPECT_LT(tau, previous) << "deeper into the wall: larger torque";
    EXPECT_GT(sim.contact_count(0), 0);
    EXPECT_LT(sim.contact_wrench(0).force_n[0], -1.0) << "the wall pushes the flange back along -x";
    EXPECT_LT(sim.distance_m(0), 1e-3) << "the flange is at the wall";
    previous = tau;
  }
  EXPECT_EQ(sim.warnings(), 0);
  // the coupling spring balances the constraint: the twin stays at the wall, the target is beyond
  EXPECT_LT(sim.q_rad()[kShoulder], home[kShoulder] + 0.25 - 0.05);
}

TEST(TwinSimulation, AMarginPlaneIsAVirtualWallForTheMarginSpheresOnly) {
  TwinModelConfig config = test::wall_model();
  // a 3 cm sphere around the flange's end (ee_site at x = 0.5 m, so its surface is at 0.53 m) and
  // a virtual wall 5 mm in front of that, 1.5 cm in front of the real wall (x = 0.55 m)
  config.margin_planes = {{"guard", {0.535, 0, 0}, {-1, 0, 0}}};
  config.margin_spheres = {{"tip", "link7", {0, 0, 0.107}, 0.03}};
  config.distance_pairs = {{"tip_guard", "geom:tip", "geom:guard"}, {"flange_wall", "geom:link7_flange", "geom:wall"}};
  TwinSimulation sim(config);
  EXPECT_NEAR(sim.distance_m(0), 0.005, 2e-3) << "the sphere starts about 5 mm from the virtual wall";
  const JointVector home = sim.q_rad();
  hold_shoulder_offset(sim, home, 0.2, 1000);
  EXPECT_LT(sim.constraint_torque_nm()[kShoulder], 0.0) << "the virtual wall pushes back";
  EXPECT_LT(sim.distance_m(0), 0.001) << "the sphere is at the virtual wall";
  EXPECT_GT(sim.distance_m(0), -0.005) << "and stays out of it";
  EXPECT_GT(sim.distance_m(1), 0.02) << "and the flange away from the real one";
  EXPECT_EQ(sim.warnings(), 0);
}

TEST(TwinSimulation, LeavesJointFrictionOutOfTheRenderedTorqueUnlessAsked) {
  TwinModelConfig config;
  config.model_path = test::model_path("panda.xml");
  config.keyframe = "ready";
  TwinSimulation plain(config);
  config.render_joint_friction = true;
  TwinSimulation with_friction(config);
  JointVector target = plain.q_rad();
  target[0] += 0.3;
  double plain_peak = 0.0;
  double friction_peak = 0.0;
  for (int k = 0; k < 300; ++k) {
    plain.step_coupled(target);
    with_friction.step_coupled(target);
    plain_peak = std::max(plain_peak, std::abs(plain.constraint_torque_nm()[0]));
    friction_peak = std::max(friction_peak, std::abs(with_friction.constraint_torque_nm()[0]));
  }
  EXPECT_LT(plain_peak, 1e-9);
  EXPECT_GT(friction_peak, 0.2) << "joint 1's frictionloss is 0.273 Nm";
}

TEST(TwinSimulation, MarginGeomsStartTheirContactAtTheActivationDistance) {
  TwinModelConfig config = test::wall_model();
  config.margin_spheres = {{"tip", "link7", {0, 0, 0.107}, 0.03}};
  config.margin_planes = {{"guard", {0.6, 0, 0}, {-1, 0, 0}}};
  config.margin_activation_m = 0.02;
  const TwinSimulation sim(config);
  const mjModel* m = sim.simulation().model();
  for (const char* name : {"tip", "guard"}) {
    const int g = mj_name2id(m, mjOBJ_GEOM, name);
    ASSERT_GE(g, 0) << name;
    EXPECT_DOUBLE_EQ(m->geom_margin[g], 0.02) << name;
  }
  EXPECT_DOUBLE_EQ(m->geom_margin[mj_name2id(m, mjOBJ_GEOM, "wall")], 0.0) << "the model's own geoms untouched";
}

// PARTI Fig. 5 (the margins keeping the operated hands apart): test/experiment/safety_margin_study_test.cpp

TEST(TwinSimulation, StepsWithoutAllocating) {
  TwinSimulation sim(test::wall_model());
  JointVector target = sim.q_rad();
  target[kShoulder] += 0.2;
  sim.step_coupled(target);
  teleop::test::ScopedAllocationCounter counter;
  for (int k = 0; k < 500; ++k) {
    sim.step_coupled(target);
    (void)sim.contact_wrench(0);
    (void)sim.distance_m(0);
  }
  sim.set_state(target, JointVector{});
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(sim.warnings(), 0);
}

TEST(TwinSimulation, RejectsAMarginOnABodyTheModelDoesNotHave) {
  TwinModelConfig config = test::wall_model();
  config.margin_spheres = {{"m", "no_such_body", {0, 0, 0}, 0.1}};
  EXPECT_THROW(TwinSimulation{config}, std::runtime_error);
  config = test::wall_model();
  config.contact_pairs = {{"p", "body:link7", "geom:no_such_geom"}};
  EXPECT_THROW(TwinSimulation{config}, std::runtime_error);
}

}  // namespace
}  // namespace teleop::twin
