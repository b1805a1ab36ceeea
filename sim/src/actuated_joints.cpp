#include "teleop/sim/actuated_joints.h"

#include <stdexcept>
#include <string_view>

namespace teleop::sim {

ActuatedJoints find_actuated_joints(const mjModel* m, const std::string& model_name, const std::string& name_prefix) {
  ActuatedJoints joints;
  for (int a = 0; a < m->nu; ++a) {
    const int j = m->actuator_trnid[2 * a];
    const bool hinge_drive = m->actuator_trntype[a] == mjTRN_JOINT && m->jnt_type[j] == mjJNT_HINGE;
    if (!hinge_drive) continue;
    const char* name = mj_id2name(m, mjOBJ_JOINT, j);
    if (!name_prefix.empty() && (name == nullptr || std::string_view(name).rfind(name_prefix, 0) != 0)) continue;
    if (joints.count == kMaxActuatedJoints) throw std::runtime_error(model_name + ": more than 32 actuated joints");
    joints.qpos[joints.count] = m->jnt_qposadr[j];
    joints.dof[joints.count] = m->jnt_dofadr[j];
    joints.actuator[joints.count] = a;
    ++joints.count;
  }
  if (joints.count == 0) {
    throw std::runtime_error(model_name + ": no actuated hinge joint" +
                             (name_prefix.empty() ? std::string() : " named " + name_prefix + "*"));
  }
  return joints;
}

}  // namespace teleop::sim
