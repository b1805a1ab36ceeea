// The "real" robot of the fidelity study (sim/plant_perturbation.h): the perturbation lands on the
// arm's links and joints exactly as drawn and recorded, within its bounds, and nowhere else; one
// seed gives one robot and one noise, bit for bit; the random stream is std::mt19937_64's.
#include "teleop/sim/plant_perturbation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {
namespace {

std::string panda() { return std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml"; }

struct Perturbed {
  MujocoModel nominal = MujocoModel::load(panda());
  MujocoModel model = MujocoModel::load(panda());
  ActuatedJoints joints = find_actuated_joints(model.model(), panda());
  AppliedPerturbation applied;
  Perturbed(const PerturbationSpec& spec, uint64_t seed) {
    applied = perturb_plant(model.model(), model.data(), joints, spec, seed);
  }
  int body(size_t i) const { return model.model()->jnt_bodyid[model.model()->actuator_trnid[2 * joints.actuator[i]]]; }
};

template <typename T>
bool same_bytes(const T* a, const T* b, int n) {
  return std::memcmp(a, b, sizeof(T) * static_cast<size_t>(n)) == 0;
}

TEST(PlantPerturbation, AppliesWhatItRecordsToTheArmsLinksAndJointsWithinTheBounds) {
  const PerturbationSpec spec;  // the documented defaults (docs/models.md, "Uncertainty")
  const Perturbed p(spec, 42);
  const mjModel* n = p.nominal.model();
  const mjModel* m = p.model.model();
  ASSERT_EQ(p.joints.count, 7u);
  ASSERT_EQ(p.applied.mass_factor.size(), 7u);
  double nominal_mass = 0.0;
  double mass = 0.0;
  for (size_t i = 0; i < p.joints.count; ++i) {
    const int b = p.body(i);
    const int dof = p.joints.dof[i];
    SCOPED_TRACE("joint " + std::to_string(i + 1));
    // within the bounds
    EXPECT_LE(std::abs(p.applied.mass_factor[i] - 1.0), spec.mass_fraction);
    EXPECT_LE(std::abs(p.applied.friction_factor[i] - 1.0), spec.friction_fraction);
    EXPECT_LE(std::abs(p.applied.armature_factor[i] - 1.0), spec.armature_fraction);
    EXPECT_GE(p.applied.damping_nms_per_rad[i], 0.0);
    EXPECT_LE(p.applied.damping_nms_per_rad[i], spec.damping_max_nms_per_rad);
    // in the model, exactly as recorded
    EXPECT_EQ(m->body_mass[b], n->body_mass[b] * p.applied.mass_factor[i]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(p.applied.com_offset_m[i][static_cast<size_t>(k)]), spec.com_offset_m);
      EXPECT_EQ(m->body_ipos[3 * b + k], n->body_ipos[3 * b + k] + p.applied.com_offset_m[i][static_cast<size_t>(k)]);
      EXPECT_EQ(m->body_inertia[3 * b + k], n->body_inertia[3 * b + k] * p.applied.mass_factor[i]);
    }
    EXPECT_EQ(m->dof_frictionloss[dof], n->dof_frictionloss[dof] * p.applied.friction_factor[i]);
    EXPECT_EQ(m->dof_damping[dof], n->dof_damping[dof] + p.applied.damping_nms_per_rad[i]);
    EXPECT_EQ(m->dof_armature[dof], n->dof_armature[dof] * p.applied.armature_factor[i]);
    nominal_mass += n->body_mass[b];
    mass += m->body_mass[b];
  }
  EXPECT_NEAR(p.applied.nominal_mass_kg, 16.062132, 1e-9);  // Gaz et al.'s links 1-7
  EXPECT_DOUBLE_EQ(p.applied.nominal_mass_kg, nominal_mass);
  EXPECT_DOUBLE_EQ(p.applied.perturbed_mass_kg, mass);
  // the base (not moved by a joint) and the world keep theirs; the subtree masses follow (mj_setConst)
  EXPECT_EQ(m->body_mass[1], n->body_mass[1]);
  EXPECT_NEAR(m->body_subtreemass[0], n->body_subtreemass[0] - nominal_mass + mass, 1e-12);
}

TEST(PlantPerturbation, MovesEveryQuantityForSomeJoint) {
  const Perturbed p(PerturbationSpec{}, 3);
  double spread_mass = 0.0;
  double spread_friction = 0.0;
  double spread_armature = 0.0;
  double damping = 0.0;
  double com = 0.0;
  for (size_t i = 0; i < 7; ++i) {
    spread_mass = std::max(spread_mass, std::abs(p.applied.mass_factor[i] - 1.0));
    spread_friction = std::max(spread_friction, std::abs(p.applied.friction_factor[i] - 1.0));
    spread_armature = std::max(spread_armature, std::abs(p.applied.armature_factor[i] - 1.0));
    damping = std::max(damping, p.applied.damping_nms_per_rad[i]);
    for (const double c : p.applied.com_offset_m[i]) com = std::max(com, std::abs(c));
  }
  // seven uniform draws each: the largest is far from 0 (P(all within a third) = 3^-7)
  EXPECT_GT(spread_mass, 0.1 / 3);
  EXPECT_GT(spread_friction, 0.3 / 3);
  EXPECT_GT(spread_armature, 0.5 / 3);
  EXPECT_GT(damping, 0.5 / 3);
  EXPECT_GT(com, 0.01 / 3);
}

TEST(PlantPerturbation, OneSeedGivesOneRobotBitForBitAndAnotherSeedAnother) {
  const Perturbed a(PerturbationSpec{}, 7);
  const Perturbed b(PerturbationSpec{}, 7);
  const Perturbed c(PerturbationSpec{}, 8);
  const mjModel* ma = a.model.model();
  const mjModel* mb = b.model.model();
  const mjModel* mc = c.model.model();
  EXPECT_TRUE(same_bytes(ma->body_mass, mb->body_mass, ma->nbody));
  EXPECT_TRUE(same_bytes(ma->body_ipos, mb->body_ipos, 3 * ma->nbody));
  EXPECT_TRUE(same_bytes(ma->body_inertia, mb->body_inertia, 3 * ma->nbody));
  EXPECT_TRUE(same_bytes(ma->dof_frictionloss, mb->dof_frictionloss, ma->nv));
  EXPECT_TRUE(same_bytes(ma->dof_damping, mb->dof_damping, ma->nv));
  EXPECT_TRUE(same_bytes(ma->dof_armature, mb->dof_armature, ma->nv));
  EXPECT_EQ(a.applied.mass_factor, b.applied.mass_factor);
  EXPECT_FALSE(same_bytes(ma->body_mass, mc->body_mass, ma->nbody));
  EXPECT_FALSE(same_bytes(ma->dof_frictionloss, mc->dof_frictionloss, ma->nv));
}

TEST(PlantPerturbation, AZeroSpecLeavesTheDynamicsAsTheyWere) {
  const PerturbationSpec none{0.0, 0.0, 0.0, 0.0, 0.0};
  const Perturbed p(none, 5);
  const mjModel* n = p.nominal.model();
  const mjModel* m = p.model.model();
  EXPECT_TRUE(same_bytes(m->body_mass, n->body_mass, m->nbody));
  EXPECT_TRUE(same_bytes(m->body_ipos, n->body_ipos, 3 * m->nbody));
  EXPECT_TRUE(same_bytes(m->body_inertia, n->body_inertia, 3 * m->nbody));
  EXPECT_TRUE(same_bytes(m->dof_frictionloss, n->dof_frictionloss, m->nv));
  EXPECT_TRUE(same_bytes(m->dof_damping, n->dof_damping, m->nv));
  EXPECT_TRUE(same_bytes(m->dof_armature, n->dof_armature, m->nv));
}

TEST(SeededRandom, DrawsFromTheStandardsMersenneTwister) {
  // the C++ standard fixes mt19937_64's 10000th output for the default seed 5489
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ULL);
  // uniform(): the top 53 bits of the engine's output
  SeededRandom random(5489);
  std::mt19937_64 reference(5489);
  EXPECT_EQ(random.uniform(), static_cast<double>(reference() >> 11) * 0x1.0p-53);
}

TEST(SeededRandom, UniformAndGaussianHaveTheirMomentsAndRepeatForOneSeed) {
  SeededRandom a(11);
  SeededRandom b(11);
  constexpr int kN = 200'000;
  double sum_u = 0.0;
  double sum_g = 0.0;
  double sum_g2 = 0.0;
  double lo = 1.0;
  double hi = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double u = a.uniform();
    ASSERT_EQ(u, b.uniform());
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum_u += u;
    const double g = a.gaussian();
    ASSERT_EQ(g, b.gaussian());
    sum_g += g;
    sum_g2 += g * g;
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_NEAR(sum_u / kN, 0.5, 0.005);
  EXPECT_NEAR(sum_g / kN, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum_g2 / kN), 1.0, 0.01);
}

TEST(SensorNoise, HasTheConfiguredSpreadPerQuantityAndRepeatsForOneSeed) {
  const SensorNoiseSpec spec{1e-4, 2e-3, 0.05};
  SensorNoise a(spec, derived_seed(9, 1));
  SensorNoise b(spec, derived_seed(9, 1));
  SensorNoise c(spec, derived_seed(9, 2));
  constexpr int kN = 50'000;
  double q2 = 0.0;
  double dq2 = 0.0;
  double tau2 = 0.0;
  bool differs = false;
  for (int i = 0; i < kN; ++i) {
    const double q = a.q_rad();
    const double dq = a.dq_radps();
    const double tau = a.tau_nm();
    ASSERT_EQ(q, b.q_rad());
    ASSERT_EQ(dq, b.dq_radps());
    ASSERT_EQ(tau, b.tau_nm());
    differs = differs || c.q_rad() != q;
    q2 += q * q;
    dq2 += dq * dq;
    tau2 += tau * tau;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(std::sqrt(q2 / kN), spec.q_rad, 0.02 * spec.q_rad);
  EXPECT_NEAR(std::sqrt(dq2 / kN), spec.dq_radps, 0.02 * spec.dq_radps);
  EXPECT_NEAR(std::sqrt(tau2 / kN), spec.tau_nm, 0.02 * spec.tau_nm);
  EXPECT_NE(derived_seed(9, 0), derived_seed(9, 1));
  EXPECT_NE(derived_seed(9, 0), derived_seed(10, 0));
}

}  // namespace
}  // namespace teleop::sim
