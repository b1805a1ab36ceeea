// Cost of the follower's 1 kHz control step, part by part, beside bare mj_step on the same
// model: controller + momentum observer + the MuJoCo arm (the "hardware"), and the whole node
// cycle with DDS. Run: build/default/bin/teleop_follower_step_bench (docs/benchmarks.md).
// Each step's share of the 1 ms budget is its time / 1000 us.
#include <benchmark/benchmark.h>

#include <cmath>

#include "teleop/common/clock.h"
#include "teleop/follower/follower_node.h"
#include "teleop/robot/mujoco_backend.h"

namespace teleop::follower {
namespace {

const std::string kSource = TELEOP_SOURCE_DIR;

FollowerConfig shipped_config() {
  return FollowerNode::parse_config(ConfigNode::load_file(kSource + "/config/nodes/follower.yaml"));
}

// a command that keeps the arm moving a little, so nothing settles into a cache-friendly rest
ValidCommand moving_command(const robot::ArmState& arm, uint64_t k) {
  ValidCommand c;
  c.mode = msg::CONTROL_JOINT_IMPEDANCE;
  for (size_t i = 0; i < 7; ++i) {
    c.q_des_rad[i] = arm.q_rad[i] + 0.01 * std::sin(1e-3 * static_cast<double>(k));
    c.stiffness[i] = 200;
    c.damping[i] = 20;
  }
  return c;
}

void BM_BareMjStep(benchmark::State& state) {
  robot::MujocoHardware hw(robot::mujoco_config(*shipped_config().hardware));
  const mjModel* m = hw.simulation().model();
  mjData* d = hw.simulation().data();
  for (auto _ : state) mj_step(m, d);
}
BENCHMARK(BM_BareMjStep);

void BM_HardwareWriteRead(benchmark::State& state) {
  robot::MujocoHardware hw(robot::mujoco_config(*shipped_config().hardware));
  robot::ArmState arm;
  JointVector tau{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(hw.write(tau));
    benchmark::DoNotOptimize(hw.read(arm));
  }
}
BENCHMARK(BM_HardwareWriteRead);

void control_step(benchmark::State& state, msg::ControlMode mode) {
  const FollowerConfig config = shipped_config();
  robot::MujocoHardware hw(robot::mujoco_config(*config.hardware));
  ArmControl control(config.control, 1e-3);
  robot::ArmState arm;
  if (hw.read(arm) != robot::HardwareStatus::kOk) state.SkipWithError("hardware read failed");
  uint64_t k = 0;
  JointVector tau{};
  for (auto _ : state) {
    ValidCommand c = moving_command(arm, k++);
    c.mode = mode;
    c.x_des_m = {0.5, 0.0, 0.7};
    c.orientation_wxyz = {0.7071067811865476, 0, 0.7071067811865476, 0};
    c.translational_stiffness_n_per_m = {1000, 1000, 1000};
    c.rotational_stiffness_nm_per_rad = {50, 50, 50};
    const auto& total = control.compute(arm, c);
    for (size_t i = 0; i < 7; ++i) tau[i] = total[static_cast<Eigen::Index>(i)] - control.gravity()[static_cast<Eigen::Index>(i)];
    benchmark::DoNotOptimize(hw.write(tau));
    benchmark::DoNotOptimize(hw.read(arm));
    control.estimate(arm);
  }
}

// controller + observer + the MuJoCo step: what the 1 kHz loop computes
void BM_ControlStepJointImpedance(benchmark::State& state) { control_step(state, msg::CONTROL_JOINT_IMPEDANCE); }
BENCHMARK(BM_ControlStepJointImpedance);
void BM_ControlStepCartesianImpedance(benchmark::State& state) { control_step(state, msg::CONTROL_CARTESIAN_IMPEDANCE); }
BENCHMARK(BM_ControlStepCartesianImpedance);

// the whole node cycle: commands polled, watchdog, limits, controllers, observer, hardware,
// JointState + WrenchStamped published (to a participant nobody listens to)
void BM_FollowerNodeCycle(benchmark::State& state) {
  runtime::NodeConfig node_config;
  node_config.name = "follower";
  transport::ParticipantConfig pc;
  pc.domain_id = 201;
  pc.name = "bench";
  pc.shm = false;
  pc.interface_whitelist = {"127.0.0.1"};
  transport::Participant participant(pc);
  runtime::NodeContext context{node_config, participant};
  FollowerNode node(shipped_config(), context);
  uint64_t index = 0;
  for (auto _ : state) {
    const int64_t now = monotonic_now_ns();
    node.cycle(CycleTick{index++, now, now});
  }
}
BENCHMARK(BM_FollowerNodeCycle);

}  // namespace
}  // namespace teleop::follower

BENCHMARK_MAIN();
