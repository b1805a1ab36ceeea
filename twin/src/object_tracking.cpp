#include "object_tracking.h"

#include <algorithm>

#include "teleop/common/clock.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/topics.h"

namespace teleop::twin {

sim::BodyState read_object_pose(const msg::ObjectPose& sample) {
  sim::BodyState s;
  transport::read_vector3(sample.world_pose().position_m(), s.position_m.data());
  transport::read_quaternion(sample.world_pose().orientation(), s.orientation_wxyz.data());
  transport::read_vector3(sample.world_twist().linear_mps(), s.linear_mps.data());
  transport::read_vector3(sample.world_twist().angular_radps(), s.angular_radps.data());
  return s;
}

ObjectTracking::ObjectTracking(const ObjectCorrectionConfig& config, const sim::MujocoModel& sim,
                               transport::Participant& participant) {
  tracked_.reserve(config.bodies.size());
  for (const std::string& name : config.bodies) {
    const std::string topic = transport::topics::kFollowerObjectPosePrefix + name;
    tracked_.push_back({name, sim.body_id(name),
                        std::make_unique<transport::Subscription<msg::ObjectPose>>(
                            participant, transport::TopicSpec<msg::ObjectPose>{topic.c_str(), transport::QosPreset::kStream}),
                        ObjectCorrection(config)});
  }
}

void ObjectTracking::apply(sim::MujocoModel& sim) {
  const double now_s = static_cast<double>(monotonic_now_ns()) * 1e-9;
  for (Tracked& t : tracked_) {
    if (t.subscription->poll() > 0) take_measurement(t, now_s);
    const CorrectionWrench w = t.correction.wrench(sim::body_state(sim.model(), sim.data(), t.body), now_s);
    mjtNum* applied = sim.data()->xfrc_applied + 6 * t.body;
    std::copy(w.force_n.begin(), w.force_n.end(), applied);
    std::copy(w.torque_nm.begin(), w.torque_nm.end(), applied + 3);
  }
}

void ObjectTracking::take_measurement(Tracked& t, double now_s) {
  const msg::ObjectPose& sample = t.subscription->latest();
  if (sample.body() != t.body_name) {
    // a publisher on the wrong topic: nothing it says is about this body
    ++t.wrong_body;
    return;
  }
  // the stamp is the remote site's wall clock (synchronised, as for every sample's age)
  const double age_s = static_cast<double>(system_now_ns() - sample.header().stamp_ns()) * 1e-9;
  (void)t.correction.measure(read_object_pose(sample), age_s, now_s);
}

void ObjectTracking::fill_report(runtime::NodeReport& report) const {
  for (const Tracked& t : tracked_) {
    report.add(*t.subscription);
    const std::string prefix = "object_" + t.body_name + "_";
    report.counters.emplace_back(prefix + "accepted", static_cast<double>(t.correction.accepted()));
    report.counters.emplace_back(prefix + "stale", static_cast<double>(t.correction.stale()));
    report.counters.emplace_back(prefix + "rejected", static_cast<double>(t.correction.non_finite()));
    report.counters.emplace_back(prefix + "clamped", static_cast<double>(t.correction.clamped()));
    report.counters.emplace_back(prefix + "wrong_body", static_cast<double>(t.wrong_body));
  }
}

void ObjectTracking::trace_columns(std::vector<std::string>& columns) const {
  for (const Tracked& t : tracked_) {
    columns.push_back("object_" + t.body_name + "_error_m");
    columns.push_back("object_" + t.body_name + "_force_n");
  }
}

double* ObjectTracking::trace_row(double* row) const {
  for (const Tracked& t : tracked_) {
    *row++ = t.correction.position_error_m();
    *row++ = t.correction.force_n();
  }
  return row;
}

}  // namespace teleop::twin
