#include "teleop/emulator/arm_drive_plants.h"

#include <stdexcept>
#include <string>

namespace teleop::emulator {

ArmDrivePlants::ArmDrivePlants(robot::MujocoHardware& arm, double step_s, const std::vector<JointMounting>& mountings)
    : arm_(arm), step_s_(step_s), channels_(arm.joints()) {
  if (mountings.size() != arm.joints()) {
    throw std::invalid_argument("the arm has " + std::to_string(arm.joints()) + " joints, " +
                                std::to_string(mountings.size()) + " drives are mounted on it");
  }
  if (arm.compensates_gravity()) {
    throw std::invalid_argument("an arm turned by drives carries its own weight through them: it must not compensate gravity");
  }
  for (size_t k = 0; k < channels_.size(); ++k) channels_[k].mounting_ = mountings[k];
  take_state();
}

void ArmDrivePlants::take_state() {
  (void)arm_.read(state_);
  for (size_t k = 0; k < channels_.size(); ++k) {
    Channel& c = channels_[k];
    const double sign = c.mounting_.inverted ? -1.0 : 1.0;
    c.sample(sign * (state_.q_rad[k] - c.mounting_.offset_rad), sign * state_.dq_radps[k]);
  }
}

void ArmDrivePlants::step() {
  for (size_t k = 0; k < channels_.size(); ++k) {
    Channel& c = channels_[k];
    const double mean_nm = c.mean_torque_nm();
    torque_nm_[k] = (c.jammed() ? 0.0 : (c.mounting_.inverted ? -mean_nm : mean_nm)) + external_nm_[k];
    if (c.jammed() && !c.held_) c.held_q_rad_ = state_.q_rad[k];
    c.held_ = c.jammed();
  }
  if (arm_.write(torque_nm_) != robot::HardwareStatus::kOk) ++refused_;
  for (size_t k = 0; k < channels_.size(); ++k) {
    held_[k] = channels_[k].held_;
    held_q_rad_[k] = channels_[k].held_q_rad_;
  }
  arm_.place_joints(held_q_rad_, held_);
  take_state();
}

}  // namespace teleop::emulator
