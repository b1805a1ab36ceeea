// The follower's side of each architecture, run in lock-step (test/support/lockstep.h): the shipped
// follower.yaml (the MuJoCo arm 5 cm in front of the wall) under scripted commands that push it
// into the wall, as the architecture's commander sends them: joint impedance from the leader
// (position_position), a Cartesian target and the leader's TDPA packets (pfc, pfc_tdpa), joint
// impedance with feed-forward from the twin (mmt). The commands of cycle k depend on k alone. The
// hashes below were taken before the architectures moved behind their registry (issue 29), on
// the enum-based follower (the nodes of authority 3952579; commit d15c1dc), with
//   build/default/bin/follower_lockstep_trace_test   (or: ctest --test-dir build/default -R FollowerLockstepTrace -V)
// (each run prints its hash): a refactoring that changes one bit of a trace fails here.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lockstep.h"
#include "teleop/follower/follower_node.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::follower {
namespace {

constexpr size_t kJoints = 7;
constexpr int kCycles = 1500;

FollowerConfig config(const std::string& architecture) {
  auto root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower.yaml");
  root.apply_override("teleoperation.architecture=" + architecture);
  // a slow cycle on a loaded machine must not trip the watchdog: the trace is the law's alone
  root.apply_override("follower.command_timeout_ms=10000");
  return FollowerNode::parse_config(root);
}

double ramp(double t) { return std::min(1.0, t); }

// the commander's side, scripted
struct ScriptedCommander {
  test::ScriptedStream<msg::JointCommand> joint;
  test::ScriptedStream<msg::CartesianCommand> cartesian;
  test::ScriptedStream<msg::TdpaEnergy> tdpa;
  test::DeliveryFence fence;

  ScriptedCommander(transport::Participant& peer, transport::Participant& node, bool twin)
      : joint(peer, node, twin ? transport::topics::kTwinCommand : transport::topics::kLeaderCommand,
              twin ? "twin" : "leader"),
        cartesian(peer, node, transport::topics::kLeaderCartesian, "leader"),
        tdpa(peer, node, transport::topics::kTdpaLeaderToFollower, "leader"),
        fence(peer, node) {
    auto& j = joint.sample();
    j.robot("follower");
    j.mode().assign(kJoints, msg::CONTROL_JOINT_IMPEDANCE);
    transport::presize(kJoints, j.q_des_rad(), j.dq_des_radps(), j.tau_ff_nm());
    j.stiffness_nm_per_rad().assign(kJoints, 200.0);
    j.damping_nms_per_rad().assign(kJoints, 10.0);
    auto& c = cartesian.sample();
    c.robot("follower");
    c.frame("base");
    c.stiffness_translational_n_per_m().x(1500);
    c.stiffness_translational_n_per_m().y(1500);
    c.stiffness_translational_n_per_m().z(1500);
    c.stiffness_rotational_nm_per_rad().x(100);
    c.stiffness_rotational_nm_per_rad().y(100);
    c.stiffness_rotational_nm_per_rad().z(100);
    c.damping_ratio(0.7);
    c.nullspace_stiffness_nm_per_rad(10.0);
    tdpa.sample().session(1);
    tdpa.sample().energy_in_j().resize(6);
    tdpa.sample().energy_out_j().resize(6);
  }

  // shoulder and elbow forward by up to 0.2 rad (the flange 4 cm past the wall), a twin's push
  void send_joint(size_t k, const std::array<double, kJoints>& home, bool feed_forward) {
    const double t = static_cast<double>(k) * 1e-3;
    auto& j = joint.sample();
    for (size_t i = 0; i < kJoints; ++i) {
      const bool moved = i == 1 || i == 3;
      j.q_des_rad()[i] = home[i] + (moved ? 0.2 * ramp(t) : 0.0);
      j.dq_des_radps()[i] = moved && t < 1.0 ? 0.2 : 0.0;
      j.tau_ff_nm()[i] = feed_forward ? 2.0 * std::sin(3.0 * t + static_cast<double>(i)) : 0.0;
    }
    ASSERT_TRUE(joint.deliver());
  }

  // the flange 8 cm towards the wall (3 cm past it) over a second, and the leader's energy totals
  void send_cartesian(size_t k, const Eigen::Vector3d& x0, const std::array<double, 4>& r0) {
    const double t = static_cast<double>(k) * 1e-3;
    auto& c = cartesian.sample();
    c.target_pose().position_m().x(x0.x() + 0.08 * ramp(t));
    c.target_pose().position_m().y(x0.y());
    c.target_pose().position_m().z(x0.z());
    c.target_pose().orientation().w(r0[0]);
    c.target_pose().orientation().x(r0[1]);
    c.target_pose().orientation().y(r0[2]);
    c.target_pose().orientation().z(r0[3]);
    c.target_twist().linear_mps().x(t < 1.0 ? 0.08 : 0.0);
    for (size_t ch = 0; ch < 6; ++ch) {
      tdpa.sample().energy_in_j()[ch] = 3e-4 * static_cast<double>(k);
      tdpa.sample().energy_out_j()[ch] = 1e-4 * static_cast<double>(k) * (1.0 + 0.1 * static_cast<double>(ch));
    }
    ASSERT_TRUE(cartesian.deliver());
    ASSERT_TRUE(tdpa.deliver());
  }
};

// the flange's orientation in the scene (w, x, y, z): what a Cartesian command holds
std::array<double, 4> flange_orientation(sim::MujocoModel& sim) {
  const int site = sim.site_id("ee_site");
  std::array<double, 4> q{};
  mju_mat2Quat(q.data(), sim.data()->site_xmat + 9 * site);
  return q;
}

// the hash of the follower's trace over kCycles lock-step cycles of `architecture`
uint64_t run(const std::string& architecture) {
  const FollowerConfig c = config(architecture);
  test::NodeHarness harness{"follower"};
  auto hardware = std::make_unique<robot::MujocoHardware>(robot::mujoco_config(*c.hardware));
  robot::MujocoHardware* sim = hardware.get();
  FollowerNode node{c, std::move(hardware), harness.context};
  const bool twin = architecture == "mmt";
  const bool cartesian = architecture == "pfc" || architecture == "pfc_tdpa";
  ScriptedCommander commander{harness.peer, harness.node_participant, twin};
  // each stream reaches two readers in the node's participant, the node's and the probe: both matched
  // before the first command, or the node might miss it
  EXPECT_TRUE(test::eventually([&] {
    if (!commander.fence.matched()) return false;
    return cartesian ? commander.cartesian.matched() && commander.tdpa.matched() : commander.joint.matched();
  }));
  std::vector<std::string> columns;
  node.trace_columns(columns);
  std::vector<double> row(columns.size());
  // the passivity controller's work, traced since the hashes were taken (issue 34), is left out
  test::HashedColumns hashed(columns, {"tdpa_dissipated_j", "tdpa_acting"});
  EXPECT_EQ(hashed.missing(), 0u) << "the follower no longer traces a column this test leaves out";
  test::TraceHash hash{"follower_" + architecture};
  std::array<double, kJoints> home{};
  Eigen::Vector3d x0 = Eigen::Vector3d::Zero();
  std::array<double, 4> r0{};
  for (size_t k = 0; k < kCycles; ++k) {
    // cycle 0 holds where the robot stands: that pose is where the commands start from
    if (k == 1) {
      std::copy_n(node.arm().q_rad.begin(), kJoints, home.begin());
      x0 = node.control().ee_position();
      r0 = flange_orientation(sim->simulation());
    }
    if (k > 0 && cartesian) commander.send_cartesian(k, x0, r0);
    if (k > 0 && !cartesian) commander.send_joint(k, home, twin);
    if (!commander.fence.pass()) {
      ADD_FAILURE() << "the fence of cycle " << k << " did not arrive";
      return 0;
    }
    node.cycle(harness.tick());
    node.trace_row(row.data());
    hash.add(hashed.of(row));
  }
  std::printf("%s: %llu rows, trace hash 0x%016llx\n", architecture.c_str(),
              static_cast<unsigned long long>(hash.rows()), static_cast<unsigned long long>(hash.value()));
  return hash.value();
}

TEST(FollowerLockstepTrace, PositionPosition) { EXPECT_EQ(run("position_position"), 0xa1e8c25599c21745ull); }

TEST(FollowerLockstepTrace, Pfc) { EXPECT_EQ(run("pfc"), 0x0075e10cc8b50fddull); }

TEST(FollowerLockstepTrace, PfcTdpa) { EXPECT_EQ(run("pfc_tdpa"), 0xaf705466d5218b24ull); }

TEST(FollowerLockstepTrace, Mmt) { EXPECT_EQ(run("mmt"), 0x082050ad2dc0ee12ull); }

}  // namespace
}  // namespace teleop::follower
