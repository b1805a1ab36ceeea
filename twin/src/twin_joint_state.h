#pragma once
// The twin's joints as it publishes them (its own state topic, lock-step's state): one arm's
// slice of the driven joints, so that a two-arm twin sends each arm on its own topic.

#include <algorithm>
#include <cstddef>

#include <teleop/msg/arm.h>

#include "teleop/twin/twin_simulation.h"

namespace teleop::twin {

/// The `count` driven joints of `sim` from `first`: q, dq, the twin's own torque
/// (`tau_measured_nm`) and the constraint torque before lambda (`tau_ext_nm`). Real-time safe
/// once the sequences hold `count` values.
inline void write_joint_state(const TwinSimulation& sim, size_t first, size_t count, msg::JointState& out) {
  auto copy = [&](const JointVector& from, std::vector<double>& to) {
    to.resize(count);
    std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(first), count, to.begin());
  };
  copy(sim.q_rad(), out.q_rad());
  copy(sim.dq_radps(), out.dq_radps());
  copy(sim.tau_nm(), out.tau_measured_nm());
  copy(sim.constraint_torque_nm(), out.tau_ext_nm());
}

}  // namespace teleop::twin
