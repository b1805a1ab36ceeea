#include "pfc_follower.h"

namespace teleop::follower {

PfcFollower::PfcFollower(transport::Participant& participant, const std::string& node_name, const std::string& arm,
                         double cycle_s, bool corrects, const runtime::TdpaSettings& settings)
    : tdpa_(participant, node_name, arm, runtime::TdpaEnd::kFollower, 6, cycle_s, corrects,
            settings.max_follower_damping),
      passive_(tdpa_, cycle_s, settings) {}

const ValidCommand* PfcFollower::correct(const ValidCommand& active, bool running, const control::Vector6& wrench) {
  tdpa_.receive();
  if (running && active.mode == msg::CONTROL_CARTESIAN_IMPEDANCE) {
    passive_.apply(active, wrench, corrected_);
    return &corrected_;
  }
  tdpa_.publish();  // the totals still go out, so the leader's observer keeps up
  return nullptr;
}

void PfcFollower::fill_report(runtime::NodeReport& report) const {
  tdpa_.fill_report(report);
  report.counters.emplace_back("tdpa_position_drift_m", passive_.position_drift_m());
}

}  // namespace teleop::follower
