#include "pfc.h"

#include <array>

#include "teleop/transport/arm_topic.h"

namespace teleop::leader {
namespace {

void set_vector3(msg::Vector3& out, double x, double y, double z) {
  out.x(x);
  out.y(y);
  out.z(z);
}

}  // namespace

PfcLeader::PfcLeader(const LeaderSetup& setup, bool corrects)
    : config_(setup.config),
      follower_wrench_(setup.peers.follower_wrench),
      command_(setup.context.participant, transport::arm_topic(transport::topics::kLeaderCartesian, setup.config.arm),
               setup.context.node.name),
      // pfc reports its energy balance too; only pfc_tdpa corrects it
      tdpa_(setup.context.participant, setup.context.node.name, setup.config.arm, runtime::TdpaEnd::kLeader, 6,
            setup.period_s, corrects, setup.config.teleoperation.tdpa.max_leader_damping) {
  setup.peers.twin_feedback.mark_optional();  // only MMT renders the twin's forces
  auto& cmd = command_.sample();
  cmd.robot("follower");
  cmd.arm(transport::arm_label(config_.arm));
  cmd.frame("base");
}

void PfcLeader::send(const MappedDevice& device) {
  auto& cmd = command_.sample();
  const Eigen::Vector3d& x = device.cartesian.position();
  const Eigen::Quaterniond r = device.cartesian.orientation();
  const control::Vector6& v = device.cartesian.twist();
  set_vector3(cmd.target_pose().position_m(), x.x(), x.y(), x.z());
  auto& o = cmd.target_pose().orientation();
  o.w(r.w());
  o.x(r.x());
  o.y(r.y());
  o.z(r.z());
  set_vector3(cmd.target_twist().linear_mps(), v[0], v[1], v[2]);
  set_vector3(cmd.target_twist().angular_radps(), v[3], v[4], v[5]);
  const CartesianGains& g = config_.cartesian;
  set_vector3(cmd.stiffness_translational_n_per_m(), g.translational_n_per_m[0], g.translational_n_per_m[1],
              g.translational_n_per_m[2]);
  set_vector3(cmd.stiffness_rotational_nm_per_rad(), g.rotational_nm_per_rad[0], g.rotational_nm_per_rad[1],
              g.rotational_nm_per_rad[2]);
  cmd.damping_ratio(g.damping_ratio);
  cmd.nullspace_stiffness_nm_per_rad(g.nullspace_stiffness_nm_per_rad);
  command_.publish();
}

bool PfcLeader::feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback, uint64_t& rejected) {
  const auto& w = follower_wrench_.latest();
  control::Vector6 wrench;
  wrench << w.force_n().x(), w.force_n().y(), w.force_n().z(), w.torque_nm().x(), w.torque_nm().y(), w.torque_nm().z();
  if (!follower_wrench_.has_sample() || !wrench.allFinite()) {
    if (follower_wrench_.has_sample()) ++rejected;
    wrench.setZero();
  }
  // the channel's leader port: f resists the command velocity v (both follower space), the
  // controller may add damping; the device then renders -f_out
  std::array<double, 6> f{};
  std::array<double, 6> v{};
  std::array<double, 6> f_out{};
  for (int i = 0; i < 6; ++i) {
    f[static_cast<size_t>(i)] = -wrench[i];
    v[static_cast<size_t>(i)] = device.cartesian.twist()[i];
  }
  (void)tdpa_.update(f, v, f_out);
  tdpa_.publish();
  control::Vector6 render;
  for (int i = 0; i < 6; ++i) render[i] = -f_out[static_cast<size_t>(i)];
  // device force for a follower-space force: scaled like the motion (power preserved)
  render.head<3>() *= config_.workspace_scale;
  // a Cartesian device (a delta, a 6-DoF mouse) takes the wrench itself: force, then moment
  if (device.kinematics == nullptr) {
    feedback.fill(0.0);
    for (int i = 0; i < 6; ++i) feedback[static_cast<size_t>(i)] = render[i];
  } else {
    device.kinematics->torque_for_wrench(render, feedback);
  }
  return follower_wrench_.age_ns(now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
}

}  // namespace teleop::leader
