#pragma once
// The PARTI studies `teleop fidelity-study` runs besides the coupling thesis's (docs/fidelity.md):
// a study file whose top-level section is `parti_twin_study:` (§3.2, parti_twin_study.h) or
// `safety_margin_study:` (§3.1 Fig. 5, safety_margin_study.h).

#include <string>

#include "teleop/experiment/fidelity_study.h"

namespace teleop::experiment {

/// Whether the file at `path` holds one of the PARTI studies. Throws ConfigError when it cannot be
/// read as YAML.
bool is_parti_study(const std::string& path);

/// Runs it (`options`: out_dir, seeds, plots), prints its report and where its files are.
/// Returns 0 when no simulation raised a MuJoCo warning, else 1. Throws ConfigError for a bad file,
/// std::runtime_error when `options.sequences` names any (these studies have none).
int run_parti_study(const std::string& path, const FidelityStudyOptions& options);

}  // namespace teleop::experiment
