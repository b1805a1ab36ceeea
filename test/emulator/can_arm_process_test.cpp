// The stiff wall through CiA 402: the follower drives an arm of emulated torque drives over the
// CANopen stack (teleop_follower_emulated_can: its `hardware: canopen` master and the drives
// turning the MuJoCo arm, in its process on virtual buses, emulated_can_arm.h), the scripted
// operator pushes it into the wall through the leader (config/experiments/stiff_wall.yaml on
// `lan`), and the table's row is the MuJoCo backend's: the operator feels the same force and the
// follower holds as close, within 10 %. Seven drives on four buses (two per bus at 1 kHz,
// docs/can_bus_budget.md), Panda-sized, with rated torques that give the target torque (0x6071,
// per mille of rated) a resolution of 9 mN m at the big joints: at 43 mN m (rated 480 mN m)
// pfc_tdpa felt 9.1-10.4 N against the simulation's 10.5-10.7 N, its passivity controller
// dissipating the quantization's chatter (docs/robots.md). The same over SocketCAN between
// processes is the vcan HIL.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "process_helpers.h"
#include "stiff_wall_runs.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

// the shipped follower with the arm behind seven emulated CiA 402 drives on four buses: gear 100
// at 90 %, 16-bit encoders, the Panda's largest torques, rated 100 / 15 mN m at the motor, and its
// joint ranges (a drive knows no model: its range is configured, as on a real arm)
std::string can_follower_config(const std::string& dir) {
  std::string drives = "  hardware: canopen_emulated\n  canopen:\n    drives:\n";
  const int max_torque_nm[7] = {87, 87, 87, 87, 12, 12, 12};
  const char* range[7] = {"-2.8973, q_max_rad: 2.8973", "-1.7628, q_max_rad: 1.7628", "-2.8973, q_max_rad: 2.8973",
                          "-3.0718, q_max_rad: -0.0698", "-2.8973, q_max_rad: 2.8973", "-0.0175, q_max_rad: 3.7525",
                          "-2.8973, q_max_rad: 2.8973"};
  for (int k = 0; k < 7; ++k) {
    drives += "      - {bus: can" + std::to_string(k / 2) + ", node: " + std::to_string(k + 1) +
              ", gear_ratio: 100, gear_efficiency: 0.9, encoder_ticks_per_rev: 65536, rated_torque_mnm: " +
              (max_torque_nm[k] == 87 ? "100" : "15") + ", max_torque_nm: " + std::to_string(max_torque_nm[k]) +
              ", q_min_rad: " + range[k] + "}\n";
  }
  return config_copy(dir, "follower.yaml", {{"  hardware: mujoco\n", drives}});
}

struct StiffWallRows {
  ResultsRow mujoco;
  ResultsRow can;
};

// the experiment and its scenarios beside the CAN follower's config, which replaces the follower
StiffWallRows stiff_wall_on_both(const std::string& architecture) {
  ProcessSite site;
  StiffWallRows rows;
  rows.mujoco = run_stiff_wall(site, source("config/experiments/stiff_wall.yaml"), architecture, "mujoco");
  const std::string experiment =
      stiff_wall_with_follower(site, "teleop_follower_emulated_can", can_follower_config(site.dir));
  rows.can = run_stiff_wall(site, experiment, architecture, "can");
  return rows;
}

void expect_same_stiff_wall(const StiffWallRows& rows) {
  ASSERT_EQ(rows.mujoco.at("status"), "ok");
  ASSERT_EQ(rows.can.at("status"), "ok");
  EXPECT_EQ(rows.can.at("stable"), rows.mujoco.at("stable")) << rows.can.at("stable_why");
  for (const char* column : {"force_felt_n", "tracking_hold_m", "force_exerted_n"}) {
    const double simulation = number(rows.mujoco, column);
    EXPECT_NEAR(number(rows.can, column), simulation, 0.1 * simulation) << column;
    ::testing::Test::RecordProperty(std::string(column) + "_ratio", std::to_string(number(rows.can, column) / simulation));
  }
  // the table of docs/robots.md (`ctest -R CanArm -V` prints it)
  for (const char* column : {"force_felt_n", "tracking_hold_m", "force_mad_n"}) {
    std::printf("%s: CAN %.4g, MuJoCo %.4g\n", column, number(rows.can, column), number(rows.mujoco, column));
  }
}

TEST(CanArm, StiffWallPositionPositionAsOnTheSimulation) {
  expect_same_stiff_wall(stiff_wall_on_both("position_position"));
}

TEST(CanArm, StiffWallPfcAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("pfc")); }

TEST(CanArm, StiffWallPfcTdpaAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("pfc_tdpa")); }

TEST(CanArm, StiffWallModelMediatedAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("mmt")); }

}  // namespace
}  // namespace teleop::test
