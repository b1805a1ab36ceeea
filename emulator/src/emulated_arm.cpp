#include "teleop/emulator/emulated_arm.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "teleop/sim/actuated_joints.h"

namespace teleop::emulator {
namespace {

constexpr double kTorqueConstant = 0.1;     // N m/A, a servo motor of a few hundred watts
constexpr double kCurrentBandwidthHz = 1e3;

std::vector<JointMounting> mountings(const robot::CanopenHardwareConfig& config) {
  std::vector<JointMounting> out;
  for (const robot::CanopenJointConfig& j : config.joints) out.push_back({j.axis.offset_rad, j.axis.inverted});
  return out;
}

}  // namespace

std::vector<double> joint_inertias(robot::MujocoHardware& arm) {
  const mjModel* m = arm.simulation().model();
  mjData* d = arm.simulation().data();
  mj_forward(m, d);  // the mass matrix at the pose now; the state itself is not changed
  std::vector<mjtNum> full(static_cast<size_t>(m->nv) * static_cast<size_t>(m->nv));
  mj_fullM(m, full.data(), d->qM);
  const sim::ActuatedJoints joints = sim::find_actuated_joints(m, "the arm");
  std::vector<double> inertias;
  for (size_t k = 0; k < joints.count; ++k) {
    const auto dof = static_cast<size_t>(joints.dof[k]);
    inertias.push_back(full[dof * static_cast<size_t>(m->nv) + dof]);
  }
  return inertias;
}

drive::EmulatedDriveConfig arm_joint_drive(const robot::CanopenJointConfig& joint, double joint_inertia_kgm2) {
  const robot::Cia402AxisConfig& a = joint.axis;
  drive::EmulatedDriveConfig c;
  c.node_id = joint.node;
  drive::EmulatedMotorParams& m = c.motor;
  m.supply_v = 48.0;
  m.resistance_ohm = 0.5;
  m.inductance_h = 0.5e-3;
  m.torque_constant_nm_per_a = kTorqueConstant;
  m.gear_ratio = a.gear_ratio;
  m.gear_efficiency = a.gear_efficiency;
  m.encoder_ticks_per_rev = a.encoder_ticks_per_rev;
  m.holding_brake = true;  // a joint under gravity: braked while the power is off
  // the own link's stops are unused (the arm is the plant) but must hold the initial angle
  m.stop_min_rad = -100.0;
  m.stop_max_rad = 100.0;
  c.rated_current_a = a.rated_torque_nm / kTorqueConstant;
  const double amps_per_joint_nm = 1.0 / (a.gear_ratio * a.gear_efficiency * kTorqueConstant);
  c.peak_current_a = 1.25 * a.max_torque_nm * amps_per_joint_nm;
  c.max_current_a = c.peak_current_a;
  drive::EmulatedControllerParams& p = c.control;
  p.current_kp_v_per_a = m.inductance_h * 2 * M_PI * kCurrentBandwidthHz;
  p.current_ki_v_per_a_s = m.resistance_ohm * 2 * M_PI * kCurrentBandwidthHz;
  // the holding quick stop: a PD (plus a little integral for the weight) on the joint, the
  // largest torque at 50 mrad
  const double stiffness_nm_per_rad = a.max_torque_nm / 0.05;
  p.position_kp_a_per_rad = stiffness_nm_per_rad * amps_per_joint_nm;
  p.position_kd_a_s_per_rad = 2.0 * std::sqrt(stiffness_nm_per_rad * joint_inertia_kgm2) * amps_per_joint_nm;
  p.position_ki_a_per_rad_s = 10.0 * p.position_kp_a_per_rad;
  p.position_integral_limit_a = c.peak_current_a;
  p.max_reference_velocity_radps = 2.0;
  c.following_error_window_rad = 1.0;
  return c;
}

EmulatedArm::EmulatedArm(robot::MujocoHardware& arm, double step_s, const robot::CanopenHardwareConfig& config,
                         const std::vector<can::CanBus*>& buses)
    : plant_(arm, step_s, mountings(config)) {
  if (buses.size() != config.joints.size()) {
    throw std::invalid_argument(std::to_string(config.joints.size()) + " drives, " + std::to_string(buses.size()) + " buses");
  }
  const std::vector<double> inertias = joint_inertias(arm);
  std::vector<drive::DriveGroupNode> nodes;
  for (size_t k = 0; k < config.joints.size(); ++k) {
    nodes.push_back({buses[k], arm_joint_drive(config.joints[k], inertias[k]), k});
  }
  group_ = std::make_unique<drive::DriveGroup>(nodes, &plant_);
}

}  // namespace teleop::emulator
