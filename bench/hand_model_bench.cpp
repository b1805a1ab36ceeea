// Cost of one step of the SVH-class hand's MuJoCo model (docs/hand.md), beside bare mj_step on
// the same model and state: the hand alone (svh_hand.xml, open, in the air) under its per-channel
// PD, and the study's scene (scene_ur5_svh.xml: UR5-class arm + hand, the index tip resting on
// the panel) under the study's whole control cycle (arm PD with gravity compensation, hand PD),
// with the couplings as equalities and as servos. Every iteration starts from the same settled
// state (restored from a snapshot: positions, velocities, controls, the solver's warm start; a
// copy of a few hundred bytes, in every benchmark alike), so the bare step sees the contact and
// the constraints the controlled one does.
// The emulator's cycle (teleop_hand_emulator, docs/hand.md): nine emulated drives stepped through
// one 4 ms cycle of the adapter's 250 Hz SYNC (the adapter on a VirtualCanBus sends SYNC and the
// targets, the drives answer; only the drives' and the plant's work is timed), turning their own
// DC-motor links (--plant motor) or the MuJoCo hand (--plant mujoco) moving freely or holding the
// grasp scene's object; the counter rtf is simulated time per CPU time, the real-time factor.
// Run: build/default/bin/teleop_hand_model_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include <cmath>
#include <memory>

#include "teleop/can/virtual_can_bus.h"
#include "teleop/experiment/hand_study.h"
#include "teleop/experiment/hand_study_simulation.h"
#include "teleop/drive/drive_group.h"
#include "teleop/hand/grasp_closer.h"
#include "teleop/hand/grasp_object.h"
#include "teleop/hand/hand_adapter.h"
#include "teleop/hand/hand_plant.h"
#include "teleop/hand/mujoco_drive_plants.h"
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

// the adapter and nine drives on a VirtualCanBus, the drives turning `plants` (null: their links)
class EmulatorRig {
 public:
  EmulatorRig(std::unique_ptr<hand::MujocoDrivePlants> plants, const hand::HandAdapterConfig& config)
      : plants_(std::move(plants)), adapter_ep_(bus_.open("adapter")), adapter_(*adapter_ep_, config) {
    std::vector<drive::DriveGroupNode> nodes;
    for (size_t k = 0; k < hand::kHandMotors; ++k) {
      endpoints_.push_back(bus_.open("drive"));
      drive::DriveGroupNode n;
      n.bus = endpoints_.back().get();
      n.config.node_id = config.node_ids[k];
      n.channel = k;
      nodes.push_back(n);
    }
    hand_ = std::make_unique<drive::DriveGroup>(nodes, plants_.get());
    while (adapter_.phase() != hand::HandPhase::kOperational && now_ns_ < 5'000'000'000) cycle();
  }
  hand::HandAdapter& adapter() { return adapter_; }
  hand::MujocoDrivePlants* plants() { return plants_.get(); }
  /// the adapter's cycle (SYNC, targets), then the drives through the 4 ms
  void adapter_cycle() { adapter_.cycle(now_ns_); }
  void drives_cycle() {
    hand_->step(kCycleS);
    now_ns_ += 4'000'000;
  }
  void cycle() {
    adapter_cycle();
    drives_cycle();
  }
  static constexpr double kCycleS = 4e-3;

 private:
  std::unique_ptr<hand::MujocoDrivePlants> plants_;
  can::VirtualCanBus bus_;
  std::unique_ptr<can::VirtualCanEndpoint> adapter_ep_;
  hand::HandAdapter adapter_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::unique_ptr<drive::DriveGroup> hand_;
  int64_t now_ns_ = 0;
};

std::unique_ptr<hand::MujocoDrivePlants> mujoco_hand(const std::string& model) {
  return std::make_unique<hand::MujocoDrivePlants>(
      hand::HandPlant(sim::MujocoModel::load(kSource + "/config/models/" + model), hand::HandCoupling::svh()), 4.8);
}

hand::HandAdapterConfig config_for(const hand::MujocoDrivePlants* plants) {
  hand::HandAdapterConfig c;
  if (plants != nullptr) {
    for (size_t k = 0; k < hand::kHandMotors; ++k)
      c.max_position_rad[k] = plants->hand().index().motor_max_rad[k] - 5e-3;
  }
  return c;
}

// every motor swinging through its range at 0.5 Hz (phase-shifted), as the vcan tracking test
void emulator_moving(benchmark::State& state, std::unique_ptr<hand::MujocoDrivePlants> plants) {
  const hand::HandAdapterConfig config = config_for(plants.get());
  EmulatorRig rig(std::move(plants), config);
  double t = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    hand::HandTargets targets;
    targets.enable = true;
    for (size_t k = 0; k < hand::kHandMotors; ++k) {
      targets.position_rad[k] =
          config.max_position_rad[k] * (0.5 - 0.3 * std::cos(M_PI * t + 0.2 * static_cast<double>(k)));
    }
    rig.adapter().set_command(targets);
    rig.adapter_cycle();
    t += EmulatorRig::kCycleS;
    state.ResumeTiming();
    rig.drives_cycle();
  }
  state.counters["rtf"] =
      benchmark::Counter(EmulatorRig::kCycleS * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  if (rig.plants() != nullptr) state.counters["mujoco_warnings"] = rig.plants()->hand().mujoco_warnings();
}

void BM_Emulator250HzMotorPlant(benchmark::State& state) { emulator_moving(state, nullptr); }
BENCHMARK(BM_Emulator250HzMotorPlant)->Unit(benchmark::kMicrosecond);

void BM_Emulator250HzMujocoHandMoving(benchmark::State& state) { emulator_moving(state, mujoco_hand("svh_hand.xml")); }
BENCHMARK(BM_Emulator250HzMujocoHandMoving)->Unit(benchmark::kMicrosecond);

// the grasp scene's object held (its support released): the contacts of a grasp in every step
void BM_Emulator250HzMujocoHandGrasping(benchmark::State& state) {
  auto plants = mujoco_hand("svh_hand_grasp.xml");
  const hand::HandAdapterConfig config = config_for(plants.get());
  EmulatorRig rig(std::move(plants), config);
  hand::GraspObject object(rig.plants()->hand());
  hand::GraspCloser closer(hand::power_grasp(config.max_position_rad));
  closer.start(rig.adapter().feedback().position_rad);
  hand::HandTargets targets;
  targets.enable = true;
  targets.current_limit_a = closer.config().current_limit_a;
  for (double t = 0.0; t < 5.0; t += EmulatorRig::kCycleS) {
    if (t >= 4.0) object.release();
    targets.position_rad = closer.update(t, rig.adapter().feedback().position_rad);
    rig.adapter().set_command(targets);
    rig.cycle();
  }
  for (auto _ : state) {
    state.PauseTiming();
    rig.adapter_cycle();
    state.ResumeTiming();
    rig.drives_cycle();
  }
  state.counters["rtf"] =
      benchmark::Counter(EmulatorRig::kCycleS * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["contacts"] = rig.plants()->hand().data()->ncon;
  state.counters["object_links"] = object.touching_links();
  state.counters["mujoco_warnings"] = rig.plants()->hand().mujoco_warnings();
}
BENCHMARK(BM_Emulator250HzMujocoHandGrasping)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace teleop

BENCHMARK_MAIN();
