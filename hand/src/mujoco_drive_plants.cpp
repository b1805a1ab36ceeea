#include "teleop/hand/mujoco_drive_plants.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace teleop::hand {

MujocoDrivePlants::MujocoDrivePlants(HandPlant hand, double torque_limit_nm) : hand_(std::move(hand)) {
  if (!(torque_limit_nm > 0) || !std::isfinite(torque_limit_nm)) {
    throw std::invalid_argument("MujocoDrivePlants: the motors' torque limit must be positive and finite");
  }
  hand_.set_motor_torque_limit(torque_limit_nm);
  sync_from_model();
}

double MujocoDrivePlants::step_s() const { return hand_.model()->opt.timestep; }

void MujocoDrivePlants::sync_from_model() {
  const HandMotorVector m = hand_.motor_positions();
  const HandMotorVector dm = hand_.motor_velocities();
  for (size_t k = 0; k < kHandMotors; ++k) channels_[k].sample(m[k], dm[k]);
}

void MujocoDrivePlants::step() {
  mjData* d = hand_.data();
  const SvhModelIndex& index = hand_.index();
  hand_.begin_step();
  for (size_t k = 0; k < kHandMotors; ++k) {
    Channel& c = channels_[k];
    last_torque_nm_[k] = c.mean_torque_nm();
    hand_.set_motor_torque(k, c.jammed() ? 0.0 : last_torque_nm_[k]);
  }
  hand_.end_step();
  for (size_t k = 0; k < kHandMotors; ++k) {
    Channel& c = channels_[k];
    // a jammed motor: its main joint stays where the jam found it (motor units = main joint,
    // times the main joint's factor, plus its offset)
    if (c.jammed()) {
      const size_t j = index.main_joint[k];
      if (!c.was_jammed_) c.jam_rad_ = c.sampled_rad();
      d->qpos[index.qpos[j]] = hand_.coupling().offsets()[j] + hand_.coupling().terms()[j].factor * c.jam_rad_;
      d->qvel[index.dof[j]] = 0.0;
    }
    c.was_jammed_ = c.jammed();
  }
  sync_from_model();
}

}  // namespace teleop::hand
