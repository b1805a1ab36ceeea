#include "twin_observations.h"

#include <algorithm>
#include <cmath>

#include "teleop/transport/joint_fields.h"
#include "teleop/transport/topics.h"

namespace teleop::twin {
namespace {

double norm3(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

TwinObservations::TwinObservations(const TwinSimulation& sim, transport::Participant& participant,
                                   const std::string& source)
    : distances_pub_(participant, transport::topics::kTwinDistances, source),
      sim_start_s_(sim.time_s()),
      min_distance_m_(sim.config().distance_range_m) {
  const PairObserver& distances = sim.distance_pairs();
  for (size_t i = 0; i < distances.size(); ++i) {
    distances_pub_.sample().pair().push_back(distances.name(i));
    distance_names_.push_back(distances.name(i));
  }
  transport::presize(distances.size(), distances_pub_.sample().distance_m());
  distance_m_.assign(distances.size(), min_distance_m_);
  const PairObserver& contacts = sim.contact_pairs();
  for (size_t i = 0; i < contacts.size(); ++i) {
    // the topic keeps its name; the spec only borrows it for the writer's creation
    contact_names_.push_back(contacts.name(i));
    const std::string topic = transport::topics::kTwinContactWrenchPrefix + contacts.name(i);
    wrench_pubs_.push_back(std::make_unique<transport::Publication<msg::WrenchStamped>>(
        participant, transport::TopicSpec<msg::WrenchStamped>{topic.c_str(), transport::QosPreset::kStream}, source));
    wrench_pubs_.back()->sample().frame("world");
  }
  contact_force_n_.assign(contacts.size(), 0.0);
}

void TwinObservations::mark_cycle(int64_t now_ns) {
  if (first_cycle_ns_ < 0) first_cycle_ns_ = now_ns;
  last_cycle_ns_ = now_ns;
}

void TwinObservations::publish(const TwinSimulation& sim) {
  auto& distances = distances_pub_.sample().distance_m();
  for (size_t i = 0; i < distances.size(); ++i) {
    distances[i] = distance_m_[i] = sim.distance_m(i);
    min_distance_m_ = std::min(min_distance_m_, distances[i]);
  }
  if (!distances.empty()) distances_pub_.publish();

  for (size_t i = 0; i < wrench_pubs_.size(); ++i) {
    const Wrench w = sim.contact_wrench(i);
    contact_force_n_[i] = norm3(w.force_n);
    peak_contact_force_n_ = std::max(peak_contact_force_n_, contact_force_n_[i]);
    transport::set_wrench(wrench_pubs_[i]->sample(), w.force_n.data(), w.torque_nm.data());
    wrench_pubs_[i]->publish();
  }
}

void TwinObservations::fill_report(runtime::NodeReport& report, const TwinSimulation& sim, bool integrated) const {
  report.add(distances_pub_);
  for (const auto& pub : wrench_pubs_) report.add(*pub);
  const double sim_s = integrated ? sim.time_s() - sim_start_s_ : 0.0;
  const double wall_s = first_cycle_ns_ < 0 ? 0.0 : static_cast<double>(last_cycle_ns_ - first_cycle_ns_) * 1e-9;
  report.counters.emplace_back("sim_time_s", sim_s);
  report.counters.emplace_back("rt_factor", wall_s > 0 ? sim_s / wall_s : 0.0);
  report.counters.emplace_back("peak_contact_force_n", peak_contact_force_n_);
  report.counters.emplace_back("min_distance_m", min_distance_m_);
  report.counters.emplace_back("mujoco_warnings", static_cast<double>(sim.warnings()));
}

void TwinObservations::trace_columns(std::vector<std::string>& columns) const {
  for (const std::string& pair : contact_names_) columns.push_back("contact_" + pair + "_n");
  for (const std::string& pair : distance_names_) columns.push_back("distance_" + pair + "_m");
}

double* TwinObservations::trace_row(double* row) const {
  row = std::copy(contact_force_n_.begin(), contact_force_n_.end(), row);
  return std::copy(distance_m_.begin(), distance_m_.end(), row);
}

}  // namespace teleop::twin
