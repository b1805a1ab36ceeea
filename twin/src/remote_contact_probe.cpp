#include "remote_contact_probe.h"

#include <stdexcept>

namespace teleop::twin {
namespace {

int geom_id(const mjModel* m, const std::string& name, const std::string& model_name) {
  const int id = mj_name2id(m, mjOBJ_GEOM, name.c_str());
  if (id < 0) throw std::runtime_error("MuJoCo model '" + model_name + "' has no geom '" + name + "'");
  return id;
}

}  // namespace

RemoteContactProbe::RemoteContactProbe(const mjModel* m, const std::string& probe, const std::string& geom,
                                       const std::string& model_name)
    : geom_(geom_id(m, geom, model_name)),
      joints_(sim::find_actuated_joints(m, model_name)),
      pair_(m, {{"correction_probe", probe, "geom:" + geom}}, model_name),
      data_(mj_makeData(m)) {
  if (!data_) throw std::runtime_error("MuJoCo could not allocate the probe's data for '" + model_name + "'");
}

double RemoteContactProbe::gap_m(const mjModel* m, const JointVector& q_rad, double range_m) {
  mjData* d = data_.get();
  for (size_t i = 0; i < joints_.count; ++i) d->qpos[joints_.qpos[i]] = q_rad[i];
  // positions only: the narrow phase needs the geoms' poses, nothing of the dynamics
  mj_kinematics(m, d);
  return pair_.distance(m, d, 0, range_m);
}

}  // namespace teleop::twin
