#include "teleop/experiment/parti_studies.h"

#include <cstdio>
#include <stdexcept>

#include "teleop/common/config.h"
#include "teleop/experiment/parti_twin_study.h"
#include "teleop/experiment/safety_margin_study.h"

namespace teleop::experiment {
namespace {

int run_twin(const std::string& path, const FidelityStudyOptions& options) {
  const PartiTwinConfig config = load_parti_twin_study(path);
  const PartiTwinResult result = run_parti_twin_study(config, options.seeds, options.out_dir, options.plots);
  std::printf("%s", format_parti_twin_markdown(config, result.runs).c_str());
  std::printf("\nreport: %s\nper phase: %s\nsignals: %s\n", result.markdown.c_str(), result.phases_csv.c_str(),
              result.trace_csv.c_str());
  if (!result.plot_error.empty()) std::printf("[fidelity-study] warning: no figures: %s\n", result.plot_error.c_str());
  for (const PartiTwinRun& r : result.runs) {
    if (r.mujoco_warnings != 0) {
      std::printf("RESULT: FAILED (a simulation raised MuJoCo warnings)\n");
      return 1;
    }
  }
  return 0;
}

int run_margins(const std::string& path, const FidelityStudyOptions& options) {
  const SafetyMarginScenario scenario = load_safety_margin_study(path);
  const SafetyMarginStudyResult result = run_safety_margin_study(scenario, options.out_dir, options.plots);
  std::printf("%s", format_safety_margin_markdown(scenario, result.cases).c_str());
  std::printf("\nreport: %s\nsignals: %s\n", result.markdown.c_str(), result.trace_csv.c_str());
  if (!result.plot_error.empty()) std::printf("[fidelity-study] warning: no figures: %s\n", result.plot_error.c_str());
  for (const SafetyMarginResult& r : result.cases) {
    if (r.warnings != 0) {
      std::printf("RESULT: FAILED (a simulation raised MuJoCo warnings)\n");
      return 1;
    }
  }
  return 0;
}

}  // namespace

bool is_parti_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  return root.has("parti_twin_study") || root.has("safety_margin_study");
}

int run_parti_study(const std::string& path, const FidelityStudyOptions& options) {
  if (!options.sequences.empty()) throw std::runtime_error(path + " has no sequences (--sequences is the thesis study's)");
  if (ConfigNode::load_file(path).has("parti_twin_study")) return run_twin(path, options);
  return run_margins(path, options);
}

}  // namespace teleop::experiment
