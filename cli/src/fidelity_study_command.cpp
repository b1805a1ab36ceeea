#include "fidelity_study_command.h"

#include <cstdio>
#include <stdexcept>

#include "config_option.h"
#include "teleop/experiment/parti_studies.h"

namespace teleop::cli {

FidelityStudyCommand::FidelityStudyCommand(CLI::App& app)
    : command_(app.add_subcommand("fidelity-study",
                                  "how good is the twin: a perturbed \"real\" arm against its lock-step replay in the "
                                  "nominal model (Tables 4.1 and 4.2), or the wiping sweep (Tables 4.3 and 4.4), "
                                  "beside the coupling thesis's numbers; or PARTI's twin studies (§3.1, §3.2)")) {
  command_
      ->add_option("study", study_path_,
                   "study YAML file, or its name in config/experiments (fidelity: "
                   "config/experiments/fidelity.yaml; wiping: config/experiments/wiping.yaml; PARTI's: "
                   "parti_twin, safety_margins)")
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
  command_->add_option("-j,--jobs", jobs_, "wiping study: worker processes for the sweep (default: the file's)")
      ->check(CLI::Range(1, 64));
}

int FidelityStudyCommand::run() const {
  // each study's own options: one given to another study is a mistake, not something to ignore
  const bool wiping = experiment::is_wiping_study(study_path_);
  if (!wiping && jobs_ > 0) throw std::invalid_argument("-j is the wiping study's; " + study_path_ + " is not one");
  // PARTI's §3.1 and §3.2 studies (parti_twin, safety_margins): their own sections and reports
  if (experiment::is_parti_study(study_path_)) return experiment::run_parti_study(study_path_, options_);
  if (wiping && (!options_.seeds.empty() || !options_.sequences.empty())) {
    throw std::invalid_argument("--seeds and --sequences are the accuracy study's; " + study_path_ +
                                " is a wiping study (it takes -j)");
  }
  return wiping ? run_wiping() : run_accuracy();
}

int FidelityStudyCommand::run_wiping() const {
  experiment::WipingStudyOptions options;
  options.out_dir = options_.out_dir;
  options.plots = options_.plots;
  options.jobs = jobs_;
  const experiment::WipingStudyConfig config = experiment::load_wiping_study(study_path_);
  const experiment::WipingStudyResult result = experiment::run_wiping_study(config, options);
  std::printf("%s", experiment::format_wiping_markdown(config, result.cells).c_str());
  std::printf("\nsweep: %zu cells in %d worker processes, %.2f s wall\nreport: %s\nwipes: %s\ntrace: %s\ntiming: %s\n",
              result.cells.size(), result.jobs, result.wall_time_s, result.markdown.c_str(), result.wipes_csv.c_str(),
              result.trace_csv.c_str(), result.timing_csv.c_str());
  if (!result.plot_error.empty()) std::printf("[fidelity-study] warning: no figures: %s\n", result.plot_error.c_str());
  if (!result.sound()) std::printf("RESULT: FAILED (a cell failed or raised MuJoCo warnings, see the wipes CSV)\n");
  return result.sound() ? 0 : 1;
}

int FidelityStudyCommand::run_accuracy() const {
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
