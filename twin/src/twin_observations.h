#pragma once
// What the twin publishes and reports about its whole scene, whatever drives it: the distances
// of the configured geometry pairs, the contact wrench of each contact pair, and in the report
// their peaks, the simulated time against the wall time and MuJoCo's warnings. Setup allocates
// (one writer per contact pair); mark_cycle() and publish() do not.

#include <memory>
#include <string>
#include <vector>

#include <teleop/msg/arm.h>
#include <teleop/msg/twin.h>

#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::twin {

class TwinObservations {
 public:
  TwinObservations(const TwinSimulation& sim, transport::Participant& participant, const std::string& source);

  /// Notes a cycle's time (the wall-time span of the run). Real-time safe.
  void mark_cycle(int64_t now_ns);
  /// Publishes the distances and contact wrenches of the simulation's current state. Real-time safe.
  void publish(const TwinSimulation& sim);

  /// The topics, then sim_time_s, rt_factor (0 without integration: hardware in the loop),
  /// peak_contact_force_n, min_distance_m, mujoco_warnings.
  void fill_report(runtime::NodeReport& report, const TwinSimulation& sim, bool integrated) const;
  /// contact_<pair>_n (the force's magnitude) per contact pair, distance_<pair>_m per distance pair.
  void trace_columns(std::vector<std::string>& columns) const;
  /// Their values as last published; returns the position after them. Real-time safe.
  double* trace_row(double* row) const;

 private:
  transport::Publication<msg::GeomDistances> distances_pub_;
  std::vector<std::unique_ptr<transport::Publication<msg::WrenchStamped>>> wrench_pubs_;
  std::vector<std::string> contact_names_;
  std::vector<std::string> distance_names_;
  std::vector<double> contact_force_n_;
  std::vector<double> distance_m_;
  double sim_start_s_ = 0.0;
  int64_t first_cycle_ns_ = -1;
  int64_t last_cycle_ns_ = 0;
  double peak_contact_force_n_ = 0.0;
  double min_distance_m_ = 0.0;
};

}  // namespace teleop::twin
