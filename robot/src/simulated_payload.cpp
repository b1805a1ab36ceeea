#include "simulated_payload.h"

#include <cstdio>
#include <stdexcept>

namespace teleop::robot {

sim::ModelAddition payload_addition(const mjModel* model, const std::string& path, const SimulatedPayload& payload) {
  const int site = mj_name2id(model, mjOBJ_SITE, payload.site.c_str());
  if (site < 0) throw std::runtime_error(path + ": no site " + payload.site + " to carry the payload");
  // the centre of mass in the frame of the site's body: the site's place plus its rotation of com_m
  mjtNum in_site[3] = {payload.com_m[0], payload.com_m[1], payload.com_m[2]};
  mjtNum in_body[3];
  mju_rotVecQuat(in_body, in_site, model->site_quat + 4 * site);
  mju_addTo3(in_body, model->site_pos + 3 * site);
  // a small solid (a 5 cm cube's inertia) so that the body is a body, its mass where the tool's is
  const double inertia = payload.mass_kg * 0.05 * 0.05 / 6.0;
  char xml[512];
  std::snprintf(xml, sizeof(xml),
                R"(<body name="teleop_payload" pos="%.9g %.9g %.9g"><inertial pos="0 0 0" mass="%.9g" diaginertia="%.9g %.9g %.9g"/></body>)",
                in_body[0], in_body[1], in_body[2], payload.mass_kg, inertia, inertia, inertia);
  const int body = model->site_bodyid[site];
  return {mj_id2name(model, mjOBJ_BODY, body), xml};
}

}  // namespace teleop::robot
