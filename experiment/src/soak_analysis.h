#pragma once
// What the soak runner hands its analysis: every process it started and every kill, and how the
// analysis reads them back from the traces (soak.h).

#include <string>
#include <vector>

#include "teleop/experiment/soak.h"

namespace teleop::experiment {

/// One process of a soaked node: its trace and report files.
struct SoakProcess {
  std::string node;
  int incarnation = 0;
  std::string trace;
  std::string report;
};

/// Fills the events' first cycles and reaction times and the result's robot checks from the
/// processes' traces. A trace that cannot be read counts as a failure.
void analyse_soak(const SoakConfig& config, const std::vector<SoakProcess>& processes, SoakResult& result);

/// The events as CSV (a header line, then one line per event).
std::string soak_csv(const SoakResult& result);

}  // namespace teleop::experiment
