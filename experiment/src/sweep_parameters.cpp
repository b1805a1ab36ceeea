#include "sweep_parameters.h"

#include <cmath>
#include <stdexcept>

namespace teleop::experiment {
namespace {

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

int axis_of(const std::string& set) { return set[set.find(':') - 1] - 'x'; }

}  // namespace

bool is_model_parameter(const std::string& set) { return set != "press_depth_m"; }

void apply_model_parameter(const SweepParameter& p, double value, sim::MujocoModel& sim) {
  mjModel* m = sim.model();
  const std::string name = p.set.substr(p.set.find(':') + 1);
  if (starts_with(p.set, "geom_pos_")) {
    m->geom_pos[3 * sim.geom_id(name) + axis_of(p.set)] = value;
  } else if (starts_with(p.set, "body_pos_")) {
    m->body_pos[3 * sim.body_id(name) + axis_of(p.set)] = value;
  } else if (starts_with(p.set, "geom_friction:")) {
    m->geom_friction[3 * sim.geom_id(name)] = value;
  } else if (starts_with(p.set, "body_angle_x:")) {
    // the whole orientation is replaced: a body mounted with a rotation about x alone (as the
    // wiper is, parts/wiper_tool.xml) keeps its meaning, the swept angle is absolute
    mjtNum* q = m->body_quat + 4 * sim.body_id(name);
    q[0] = std::cos(0.5 * value);
    q[1] = std::sin(0.5 * value);
    q[2] = 0.0;
    q[3] = 0.0;
  } else {
    throw std::invalid_argument("'" + p.set + "' does not change the model");
  }
}

}  // namespace teleop::experiment
