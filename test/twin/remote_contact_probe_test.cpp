// The follower's pose in the twin's model (RemoteContactProbe) and the twin's movable environment:
// a geom moved at load (model error) or between steps (correction) is where the probe and the
// simulation see it.
#include "remote_contact_probe.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "allocation_counter.h"
#include "teleop/twin/twin_simulation.h"
#include "twin_test_util.h"

namespace teleop::twin {
namespace {

std::array<double, 3> geom_pos(const TwinSimulation& sim, int geom) {
  const mjtNum* p = sim.simulation().model()->geom_pos + 3 * geom;
  return {p[0], p[1], p[2]};
}

TEST(RemoteContactProbe, MeasuresTheSameGapAsTheSimulationAtTheSamePose) {
  TwinSimulation sim(test::wall_model());
  RemoteContactProbe probe(sim.simulation().model(), "geom:link7_flange", "wall", "scene_wall.xml");
  const double gap = probe.gap_m(sim.simulation().model(), sim.q_rad(), 0.5);
  EXPECT_NEAR(gap, sim.distance_m(0), 1e-9);
  EXPECT_NEAR(gap, 0.05, 0.01) << "the keyframe holds the flange 5 cm in front of the wall";
}

TEST(RemoteContactProbe, SeesTheGeomWhereItWasMoved) {
  TwinSimulation sim(test::wall_model());
  RemoteContactProbe probe(sim.simulation().model(), "body:link7", "wall", "scene_wall.xml");
  const double before = probe.gap_m(sim.simulation().model(), sim.q_rad(), 0.5);
  std::array<double, 3> pos = geom_pos(sim, probe.geom());
  pos[0] -= 0.02;  // 2 cm towards the arm
  sim.set_geom_position(probe.geom(), pos);
  EXPECT_NEAR(probe.gap_m(sim.simulation().model(), sim.q_rad(), 0.5), before - 0.02, 1e-9);
  // and so does the simulation from its next step on
  const double sim_before = sim.distance_m(0);
  sim.step_coupled(sim.q_rad());
  EXPECT_NEAR(sim.distance_m(0), sim_before - 0.02, 1e-4);
}

TEST(RemoteContactProbe, GapFollowsTheJoints) {
  TwinSimulation sim(test::wall_model());
  RemoteContactProbe probe(sim.simulation().model(), "body:link7", "wall", "scene_wall.xml");
  JointVector q = sim.q_rad();
  const double home = probe.gap_m(sim.simulation().model(), q, 0.5);
  q[test::kShoulder] += 0.1;  // towards the wall
  EXPECT_LT(probe.gap_m(sim.simulation().model(), q, 0.5), home - 0.01);
  q[test::kShoulder] += 0.3;  // well into it
  EXPECT_LT(probe.gap_m(sim.simulation().model(), q, 0.5), 0.0) << "behind the surface: negative";
}

TEST(RemoteContactProbe, GapDoesNotAllocate) {
  TwinSimulation sim(test::wall_model());
  RemoteContactProbe probe(sim.simulation().model(), "body:link7", "wall", "scene_wall.xml");
  JointVector q = sim.q_rad();
  teleop::test::ScopedAllocationCounter allocations;
  for (int k = 0; k < 100; ++k) {
    q[test::kShoulder] += 0.002;
    (void)probe.gap_m(sim.simulation().model(), q, 0.5);
  }
  EXPECT_EQ(allocations.count(), 0u);
}

TEST(RemoteContactProbe, NamesAMissingGeomOrProbe) {
  TwinSimulation sim(test::wall_model());
  const mjModel* m = sim.simulation().model();
  try {
    RemoteContactProbe(m, "body:link7", "no_such_wall", "scene_wall.xml");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_wall"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RemoteContactProbe(m, "body:no_such_link", "wall", "scene_wall.xml"), std::runtime_error);
}

TEST(TwinSimulation, AppliesTheConfiguredGeomOffsetsAtLoad) {
  TwinSimulation exact(test::wall_model());
  TwinModelConfig config = test::wall_model();
  config.geom_offsets = {{"wall", {0.02, 0.0, 0.0}}};
  TwinSimulation moved(config);
  EXPECT_NEAR(moved.distance_m(0), exact.distance_m(0) + 0.02, 1e-9) << "the twin's wall 2 cm further away";
  config.geom_offsets = {{"no_such_geom", {0.02, 0.0, 0.0}}};
  EXPECT_THROW(TwinSimulation{config}, std::out_of_range);
}

}  // namespace
}  // namespace teleop::twin
