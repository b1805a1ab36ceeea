#include "teleop/sim/body_state.h"

#include <algorithm>

namespace teleop::sim {

BodyState body_state(const mjModel* m, const mjData* d, int body) {
  BodyState s;
  std::copy_n(d->xpos + 3 * body, 3, s.position_m.begin());
  std::copy_n(d->xquat + 4 * body, 4, s.orientation_wxyz.begin());
  // MuJoCo's 6D velocity is [angular; linear]; world-aligned (flg_local 0) at the body's frame
  mjtNum velocity[6];
  mj_objectVelocity(m, d, mjOBJ_XBODY, body, velocity, 0);
  std::copy_n(velocity, 3, s.angular_radps.begin());
  std::copy_n(velocity + 3, 3, s.linear_mps.begin());
  return s;
}

}  // namespace teleop::sim
