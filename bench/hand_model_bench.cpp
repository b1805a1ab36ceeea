// Cost of one step of the SVH-class hand's MuJoCo model (docs/hand.md), beside bare mj_step on
// the same model and state: the hand alone (svh_hand.xml, open, in the air) under its per-channel
// PD, and the study's scene (scene_ur5_svh.xml: UR5-class arm + hand, the index tip resting on
// the panel) under the study's whole control cycle (arm PD with gravity compensation, hand PD),
// with the couplings as equalities and as servos. Every iteration starts from the same settled
// state (restored from a snapshot: positions, velocities, controls, the solver's warm start; a
// copy of a few hundred bytes, in every benchmark alike), so the bare step sees the contact and
// the constraints the controlled one does.
// Run: build/default/bin/teleop_hand_model_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "teleop/experiment/hand_study.h"
#include "teleop/experiment/hand_study_simulation.h"
#include "teleop/hand/hand_plant.h"
#include "teleop/hand/position_control.h"

namespace teleop {
namespace {

const std::string kSource = TELEOP_SOURCE_DIR;

// the state a step starts from
class Snapshot {
 public:
  Snapshot(const mjModel* m, const mjData* d)
      : qpos_(d->qpos, d->qpos + m->nq),
        qvel_(d->qvel, d->qvel + m->nv),
        warmstart_(d->qacc_warmstart, d->qacc_warmstart + m->nv),
        applied_(d->qfrc_applied, d->qfrc_applied + m->nv),
        ctrl_(d->ctrl, d->ctrl + m->nu),
        time_(d->time) {}
  void restore(mjData* d) const {
    std::copy(qpos_.begin(), qpos_.end(), d->qpos);
    std::copy(qvel_.begin(), qvel_.end(), d->qvel);
    std::copy(warmstart_.begin(), warmstart_.end(), d->qacc_warmstart);
    std::copy(applied_.begin(), applied_.end(), d->qfrc_applied);
    std::copy(ctrl_.begin(), ctrl_.end(), d->ctrl);
    d->time = time_;
  }

 private:
  std::vector<mjtNum> qpos_, qvel_, warmstart_, applied_, ctrl_;
  mjtNum time_;
};

// the hand alone, half closed (every motor at half its range) and held there for 0.5 s
struct HeldHand {
  hand::HandPlant plant{sim::MujocoModel::load(kSource + "/config/models/svh_hand.xml"), hand::HandCoupling::svh()};
  hand::HandPositionControl control{plant, hand::CouplingMode::kConstraint, 40.0, 1.0};
  hand::HandMotorVector target{};
  hand::HandMotorVector rest{};
  HeldHand() {
    plant.mujoco().reset("open");
    for (size_t k = 0; k < hand::kHandMotors; ++k) target[k] = 0.5 * plant.index().motor_max_rad[k];
    while (plant.data()->time < 0.5) step();
  }
  void step() {
    plant.begin_step();
    control.apply(plant, target, rest);
    plant.end_step();
  }
};

void BM_HandAloneBareMjStep(benchmark::State& state) {
  HeldHand hand;
  const Snapshot start(hand.plant.model(), hand.plant.data());
  for (auto _ : state) {
    start.restore(hand.plant.data());
    mj_step(hand.plant.model(), hand.plant.data());
  }
  state.counters["constraint_rows"] = hand.plant.data()->nefc;
}
BENCHMARK(BM_HandAloneBareMjStep);

// mj_step1, the 9 channels' PD, mj_step2: what a plant behind emulated drives would cost
void BM_HandAlonePlantStep(benchmark::State& state) {
  HeldHand hand;
  const Snapshot start(hand.plant.model(), hand.plant.data());
  for (auto _ : state) {
    start.restore(hand.plant.data());
    hand.step();
  }
  state.counters["constraint_rows"] = hand.plant.data()->nefc;
}
BENCHMARK(BM_HandAlonePlantStep);

// the study's scene held in "test" from the start, the model's own inertias, settled for 1.5 s
experiment::HandStudySimulation resting_scene(hand::CouplingMode coupling) {
  experiment::HandStudyConfig config = experiment::load_hand_study(kSource + "/config/experiments/hand_contact.yaml");
  config.path = {{"test", 0.0}};
  experiment::HandStudyRun run;
  run.name = "bench";
  run.coupling = coupling;
  experiment::HandStudySimulation simulation(config, run);
  while (simulation.time_s() < 1.5) simulation.step();
  return simulation;
}

// the controllers' last torques frozen in ctrl: the same contact, the same constraints
void BM_SceneBareMjStep(benchmark::State& state) {
  experiment::HandStudySimulation simulation = resting_scene(hand::CouplingMode::kConstraint);
  hand::HandPlant& plant = simulation.plant();
  const Snapshot start(plant.model(), plant.data());
  for (auto _ : state) {
    start.restore(plant.data());
    mj_step(plant.model(), plant.data());
  }
  state.counters["contacts"] = plant.data()->ncon;
  state.counters["constraint_rows"] = plant.data()->nefc;
}
BENCHMARK(BM_SceneBareMjStep);

void scene_study_step(benchmark::State& state, hand::CouplingMode coupling) {
  experiment::HandStudySimulation simulation = resting_scene(coupling);
  const Snapshot start(simulation.plant().model(), simulation.plant().data());
  for (auto _ : state) {
    start.restore(simulation.plant().data());
    simulation.step();
  }
  state.counters["contacts"] = simulation.plant().data()->ncon;
  state.counters["constraint_rows"] = simulation.plant().data()->nefc;
}
void BM_SceneStudyStepCouplingsAsEqualities(benchmark::State& state) {
  scene_study_step(state, hand::CouplingMode::kConstraint);
}
BENCHMARK(BM_SceneStudyStepCouplingsAsEqualities);
void BM_SceneStudyStepCouplingsAsServos(benchmark::State& state) {
  scene_study_step(state, hand::CouplingMode::kServo);
}
BENCHMARK(BM_SceneStudyStepCouplingsAsServos);

}  // namespace
}  // namespace teleop

BENCHMARK_MAIN();
