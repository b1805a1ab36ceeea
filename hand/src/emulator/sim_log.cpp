#include "sim_log.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace teleop::hand::emulator {

SimLog::SimLog(const std::string& path, double interval_s)
    : file_(std::fopen(path.c_str(), "w")), interval_s_(interval_s) {
  if (!file_) throw std::runtime_error("--sim-log " + path + ": " + std::strerror(errno));
  std::fputs("t_s,object_x_m,object_y_m,object_z_m,object_supported,object_contacts,object_links,object_force_n",
             file_.get());
  for (const auto name : kHandJointNames)
    std::fprintf(file_.get(), ",q_%.*s", static_cast<int>(name.size()), name.data());
  for (const auto name : kHandMotorNames)
    std::fprintf(file_.get(), ",tau_%.*s", static_cast<int>(name.size()), name.data());
  std::fputc('\n', file_.get());
  std::fflush(file_.get());
}

void SimLog::sample(double t_s, const MujocoDrivePlants& plants, const GraspObject* object) {
  if (t_s < next_s_) return;
  next_s_ = t_s + interval_s_;
  std::FILE* f = file_.get();
  std::fprintf(f, "%.4f", t_s);
  if (object != nullptr) {
    const auto p = object->position_m();
    std::fprintf(f, ",%.6f,%.6f,%.6f,%d,%d,%d,%.4f", p[0], p[1], p[2], object->supported() ? 1 : 0,
                 object->hand_contacts(), object->touching_links(), object->hand_contact_force_n());
  } else {
    std::fputs(",,,,,,,", f);
  }
  for (const double q : plants.hand().joint_positions()) std::fprintf(f, ",%.7f", q);
  for (const double tau : plants.last_torque_nm()) std::fprintf(f, ",%.5f", tau);
  std::fputc('\n', f);
  std::fflush(f);
}

}  // namespace teleop::hand::emulator
