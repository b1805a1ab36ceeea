#pragma once
// The arm's state in the twin's simulation as the controllers take it: shared by the sweeps'
// scenarios (the press and the wiping cell), which run the controllers on the twin in process.

#include <cstddef>

#include "teleop/control/arm_dynamics.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::experiment {

inline control::ArmState arm_state(const twin::TwinSimulation& sim) {
  control::ArmState s;
  for (int i = 0; i < control::kDof; ++i) {
    s.q[i] = sim.q_rad()[static_cast<size_t>(i)];
    s.dq[i] = sim.dq_radps()[static_cast<size_t>(i)];
  }
  return s;
}

}  // namespace teleop::experiment
