#include "fidelity_study_command.h"

#include <cstdio>

#include "config_option.h"
#include "teleop/experiment/parti_studies.h"

namespace teleop::cli {

FidelityStudyCommand::FidelityStudyCommand(CLI::App& app)
    : command_(app.add_subcommand("fidelity-study",
                                  "how good is the twin: a perturbed \"real\" arm against its lock-step replay in the "
                                  "nominal model, beside the coupling thesis's Tables 4.1 and 4.2")) {
  command_
      ->add_option("study", study_path_,
                   "fidelity study YAML file, or its name in config/experiments (fidelity: "
                   "config/experiments/fidelity.yaml; PARTI's: parti_twin, safety_margins)")
      ->required()
      ->transform(named_config("experiments"))
      ->check(CLI::ExistingFile);
  command_->add_option("-o,--out", options_.out_dir,
                       "folder for the CSVs, the report and the figures (default: a new folder in /tmp)");
  command_->add_option("--seeds", options_.seeds, "the \"real\" robots' seeds (comma-separated; default: the file's)")
      ->delimiter(',');
  command_->add_option("--sequences", options_.sequences, "only these sequences (comma-separated names)")
      ->delimiter(',');
  command_->add_flag("--no-plots{false}", options_.plots, "no figures");
}

int FidelityStudyCommand::run() const {
  // PARTI's §3.1 and §3.2 studies (parti_twin, safety_margins): their own sections and reports
  if (experiment::is_parti_study(study_path_)) return experiment::run_parti_study(study_path_, options_);
  const experiment::FidelityStudyConfig config = experiment::load_fidelity_study(study_path_);
  const experiment::FidelityStudyResult result = experiment::run_fidelity_study(config, options_);
  std::printf("%s", experiment::format_fidelity_markdown(config, result.runs).c_str());
  std::printf("\nreport: %s\nper pose and movement: %s\nruns: %s\nsignals: %s\n", result.markdown.c_str(),
              result.segments_csv.c_str(), result.runs_csv.c_str(), result.trace_csv.c_str());
  if (!result.plot_error.empty()) std::printf("[fidelity-study] warning: no figures: %s\n", result.plot_error.c_str());
  if (!result.sound()) std::printf("RESULT: FAILED (a simulation raised MuJoCo warnings, see runs)\n");
  return result.sound() ? 0 : 1;
}

}  // namespace teleop::cli
