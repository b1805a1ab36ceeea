// Physical feasibility of the box task's plan (docs/box_task.md): both arms of scene_box_shelf.xml
// under joint impedance along the committed trajectories, read as the leader reads them, with no
// network in between: the ideal baseline every teleoperation architecture is compared with.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "teleop/control/controllers.h"
#include "joint_trajectory.h"
#include "teleop/sim/mujoco_model.h"
#include "box_plan.h"
#include "teleop/box_task/box_task_probe.h"

namespace teleop::box_task {
namespace {

std::string source(const std::string& relative) { return std::string(TELEOP_SOURCE_DIR) + "/" + relative; }

/// One arm of the scene driven by joint impedance along its trajectory; the controller's model
/// is the single-arm model (left_arm.xml / right_arm.xml), as the follower's would be.
class DrivenArm {
 public:
  DrivenArm(const sim::MujocoModel& scene, Side side, const control::JointImpedance::Gains& gains)
      : model_(sim::MujocoModel::load(source("config/models/" + std::string(side_name(side)) + "_arm.xml"))),
        dynamics_(model_.model(), std::string(side_name(side)) + "_ee_site"),
        controller_(dynamics_, gains),
        trajectory_(leader::JointTrajectory::load_csv(
            source("config/trajectories/box_task_" + std::string(side_name(side)) + ".csv"), control::kDof)) {
    for (int j = 0; j < control::kDof; ++j) {
      const std::string joint = std::string(side_name(side)) + "_joint" + std::to_string(j + 1);
      qpos_[j] = scene.joint_qpos_address(joint);
      dof_[j] = scene.joint_dof_address(joint);
      actuator_[j] = scene.actuator_id(std::string(side_name(side)) + "_motor" + std::to_string(j + 1));
    }
  }

  /// Sets the arm's motor torques for the state in `d` and the trajectory at `t_s`.
  void control(mjData* d, double t_s) {
    JointVector q_d;
    JointVector dq_d;
    trajectory_.sample(t_s, q_d, dq_d);
    control::ArmState state;
    control::ArmCommand command;
    for (int j = 0; j < control::kDof; ++j) {
      state.q[j] = d->qpos[qpos_[j]];
      state.dq[j] = d->qvel[dof_[j]];
      command.q_d[j] = q_d[static_cast<size_t>(j)];
      command.dq_d[j] = dq_d[static_cast<size_t>(j)];
    }
    const control::JointVector tau = controller_.compute(state, command);
    for (int j = 0; j < control::kDof; ++j) d->ctrl[actuator_[j]] = tau[j];
  }

  double duration_s() const { return trajectory_.duration_s(); }

 private:
  sim::MujocoModel model_;
  control::ArmDynamics dynamics_;
  control::JointImpedance controller_;
  leader::JointTrajectory trajectory_;
  int qpos_[control::kDof];
  int dof_[control::kDof];
  int actuator_[control::kDof];
};

/// Runs the whole task in scene_box_shelf.xml from "home", one sample per millisecond.
BoxTaskSeries run_task(const control::JointImpedance::Gains& gains) {
  sim::MujocoModel scene = sim::MujocoModel::load(source("config/models/scene_box_shelf.xml"));
  scene.reset("home");
  DrivenArm left(scene, Side::kLeft, gains);
  DrivenArm right(scene, Side::kRight, gains);
  const BoxTaskProbe probe(scene.model());
  BoxTaskSeries series;
  const double end_s = left.duration_s() + 1.0;  // and a second to come to rest
  while (scene.data()->time < end_s) {
    mjData* d = scene.data();
    left.control(d, d->time);
    right.control(d, d->time);
    // the base's velocity servos keep their ctrl 0 from the reset: the base stands still
    mj_step(scene.model(), d);
    series.append(probe.sample(scene.model(), d));
  }
  for (int w = 0; w < mjNWARNING; ++w) EXPECT_EQ(scene.data()->warning[w].number, 0) << "MuJoCo warning " << w;
  return series;
}

/// Joint impedance of the follower's arms: shoulder and elbow joints at `stiffness` / `damping`,
/// the light wrist joints softer (their damping acts explicitly in a 1 ms step: D dt / I must stay
/// well below 2), as in config/nodes/follower.yaml's position PD.
control::JointImpedance::Gains follower_gains(double stiffness, double damping) {
  control::JointImpedance::Gains gains;
  gains.stiffness << stiffness, stiffness, stiffness, stiffness, 250, 150, 50;
  gains.damping << damping, damping, damping, damping, 10, 10, 5;
  return gains;
}

struct GainCase {
  double stiffness;
  double damping;
};

void PrintTo(const GainCase& gains, std::ostream* os) { *os << "K " << gains.stiffness << " D " << gains.damping; }

class BoxTaskFeasibility : public testing::TestWithParam<GainCase> {};

TEST_P(BoxTaskFeasibility, PlacesTheBoxInTheShelfWhenBothArmsTrackThePlanUnderJointImpedance) {
  const sim::MujocoModel scene = sim::MujocoModel::load(source("config/models/scene_box_shelf.xml"));
  const BoxTaskSeries series = run_task(follower_gains(GetParam().stiffness, GetParam().damping));
  const BoxTaskMetrics m = evaluate_box_task(series, shelf_region(scene.model()));
  const Eigen::Vector3d end = series.samples.back().box_m;
  std::printf("K %.0f D %.0f: success %d, task time %.2f s, carry %.2f s, squeeze %.1f-%.1f N (variation %.2f / %.2f N), "
              "slip %.2f mm, dropped %d, arm collision %.2f N, box at (%.4f, %.4f, %.4f) m\n",
              GetParam().stiffness, GetParam().damping, m.success, m.task_time_s, m.carry_time_s,
              std::min(m.squeeze_min_n[0], m.squeeze_min_n[1]),
              std::max(m.squeeze_min_n[0] + m.squeeze_variation_n[0], m.squeeze_min_n[1] + m.squeeze_variation_n[1]),
              m.squeeze_variation_n[0], m.squeeze_variation_n[1], m.slip_mm, m.dropped, m.max_arm_collision_n, end.x(),
              end.y(), end.z());
  EXPECT_TRUE(m.success);
  EXPECT_FALSE(m.dropped);
  EXPECT_LT(m.task_time_s, 13.0);  // placed before the plan's release ends (13.5 s)
  EXPECT_GT(m.carry_time_s, 5.0);  // held off its supports from the lift to the shelf floor
  // friction holds the box: at least twice its weight over mu = 0.8 on both hands together
  EXPECT_GT(std::min(m.squeeze_min_n[0], m.squeeze_min_n[1]), 2 * 9.81 / (2 * 0.8));
  EXPECT_LT(m.slip_mm, 8.0);
  EXPECT_LT(m.max_arm_collision_n, 0.5);  // no arm touches furniture, the body or the other arm
}

INSTANTIATE_TEST_SUITE_P(JointGains, BoxTaskFeasibility,
                         testing::Values(GainCase{800, 40}, GainCase{600, 30}, GainCase{1000, 50}),
                         [](const testing::TestParamInfo<GainCase>& param) {
                           return "K" + std::to_string(static_cast<int>(param.param.stiffness));
                         });

}  // namespace
}  // namespace teleop::box_task
