#pragma once
// The metrics of one run of the two-arm box task (docs/box_task.md): the task's own (success,
// time, squeeze variation, slip) from the follower's box-task columns, and each arm's stability
// signals (MAD, TDPA energy, saturation, safe hold) from its "<arm>_" columns.

#include "teleop/experiment/analysis.h"
#include "teleop/box_task/box_task_metrics.h"

namespace teleop::experiment {

/// The follower trace's box-task columns (box_task::kBoxTaskColumns, written with
/// follower.trace_box_task) as a series. Throws TraceError naming a missing column.
box_task::BoxTaskSeries box_task_series(const Trace& follower);

/// The stability signals of RunMetrics over all `config.arms`, each the worst arm's: MAD of the
/// follower's joints in the hold window (mean over the arm's joints), the smallest TDPA energy of
/// either end, the largest saturated and safe-hold fractions. The stiff wall's force and
/// tracking metrics stay NaN. Throws TraceError naming a missing column.
RunMetrics analyse_arms(const Trace& leader, const Trace& follower, const AnalysisConfig& config);

}  // namespace teleop::experiment
