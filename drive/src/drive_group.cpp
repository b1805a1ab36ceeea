#include "teleop/drive/drive_group.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::drive {

DriveGroup::DriveGroup(const std::vector<DriveGroupNode>& nodes, SharedDrivePlant* plant) : plant_(plant) {
  if (plant_ != nullptr) {
    plant_step_s_ = plant_->step_s();
    plant_step_ns_ = std::isfinite(plant_step_s_) ? std::llround(plant_step_s_ * 1e9) : 0;
    // at least a nanosecond: a step that rounds to 0 ns would never use up the pending time
    if (plant_step_ns_ < 1) {
      throw std::invalid_argument("DriveGroup: the shared plant's step must be finite and at least 1 ns");
    }
  }
  std::vector<bool> taken(plant_ != nullptr ? plant_->channels() : 0, false);
  for (const DriveGroupNode& node : nodes) {
    if (node.bus == nullptr) throw std::invalid_argument("DriveGroup: node without a bus");
    if (plant_ == nullptr) {
      drives_.push_back(std::make_unique<EmulatedDrive>(*node.bus, node.config));
      continue;
    }
    if (node.channel >= taken.size()) {
      throw std::invalid_argument("DriveGroup: node " + std::to_string(node.config.node_id) + " turns channel " +
                                  std::to_string(node.channel) + ", the plant has " + std::to_string(taken.size()));
    }
    if (taken[node.channel]) {
      throw std::invalid_argument("DriveGroup: channel " + std::to_string(node.channel) +
                                  " is turned by two drives (node " + std::to_string(node.config.node_id) + ")");
    }
    taken[node.channel] = true;
    drives_.push_back(std::make_unique<EmulatedDrive>(*node.bus, node.config, plant_->channel(node.channel)));
  }
}

void DriveGroup::step(double dt_s) {
  if (!(dt_s >= 0) || !std::isfinite(dt_s)) return;
  if (plant_ == nullptr) {
    for (auto& d : drives_) d->step(dt_s);
    time_ns_ += std::llround(dt_s * 1e9);
    return;
  }
  // lock-step: every drive through one plant step, then the plant
  pending_ns_ += std::llround(dt_s * 1e9);
  while (pending_ns_ >= plant_step_ns_) {
    for (auto& d : drives_) d->step(plant_step_s_);
    plant_->step();
    ++plant_steps_;
    pending_ns_ -= plant_step_ns_;
    time_ns_ += plant_step_ns_;
  }
}

}  // namespace teleop::drive
