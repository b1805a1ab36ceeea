// Whether a run's numbers can be trusted, and what the follower's safety did in it: the verdict
// of an experiment reports a run that sat in its hold or latched a reflex as what it was, and a
// run whose robot followed late (discovery) as invalid rather than as a result.
#include <teleop/msg/status.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "teleop/experiment/analysis.h"

namespace teleop::experiment {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();

// the time [s after t0_s] of the first row whose `column` satisfies `met`; kNever: none
template <class Predicate>
double first_time(const Trace& trace, const std::string& column, double t0_s, Predicate met) {
  const std::vector<double>& v = trace.column(column);
  for (size_t i = 0; i < v.size(); ++i) {
    if (met(v[i])) return trace.t_s[i] - t0_s;
  }
  return kNever;
}

}  // namespace

void analyse_run_health(const Trace& leader, const Trace& follower, const std::string& prefix, RunMetrics& m) {
  const double t0_s = operator_start_s(leader, prefix);
  // traces of older releases lack these columns: their runs are not judged on them
  if (follower.has(prefix + "reflex")) {
    const std::vector<double>& reflex = follower.column(prefix + "reflex");
    double latches = 0;
    double before = 0;
    for (const double cause : reflex) {
      if (cause > 0 && before <= 0) {
        // the first latch of the run (of its first arm that latched, on a two-arm robot)
        if (std::isnan(m.reflex_cause) || m.reflex_cause == 0) m.reflex_cause = cause;
        ++latches;
      }
      before = cause;
    }
    m.reflex_latches = std::isnan(m.reflex_latches) ? latches : m.reflex_latches + latches;
    if (latches == 0 && std::isnan(m.reflex_cause)) m.reflex_cause = 0;
  }
  if (follower.has(prefix + "cmd_session") && leader.has(prefix + "state")) {
    const double followed = first_time(follower, prefix + "cmd_session", t0_s, [](double s) { return s > 0; });
    const double in_command = first_time(leader, prefix + "state", t0_s,
                                         [](double s) { return s == static_cast<double>(msg::STATE_RUNNING); });
    // flows that matched before the operator began (its clock waits for them) matched at 0
    const double matched = std::fmax(0.0, std::fmax(followed, in_command));
    m.flows_matched_s = std::isnan(m.flows_matched_s) ? matched : std::fmax(m.flows_matched_s, matched);
  }
}

std::string invalid_reason(const RunMetrics& m, const AnalysisConfig& config) {
  const double limit_s = flows_matched_limit_s(config);
  if (!(m.flows_matched_s > limit_s)) return {};
  if (std::isinf(m.flows_matched_s)) {
    return "the flows never all matched (the leader never in command, or the follower never followed a command): "
           "its numbers are no result";
  }
  char text[224];
  std::snprintf(text, sizeof text,
                "the flows matched %.2f s after the operator began (limit %.2f s: discovery was late, the operator "
                "moved a robot that did not follow yet): its numbers are no result; run it again",
                m.flows_matched_s, limit_s);
  return text;
}

}  // namespace teleop::experiment
