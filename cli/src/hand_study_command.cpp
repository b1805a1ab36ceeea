#include "hand_study_command.h"

#include <algorithm>
#include <cstdio>

#include "config_option.h"

namespace teleop::cli {

HandStudyCommand::HandStudyCommand(CLI::App& app)
    : command_(app.add_subcommand("hand-study",
                                  "the SVH hand study in MuJoCo: joint MAD at rest in contact and the "
                                  "fingertip force, beside the paper's Gazebo and MuJoCo tables")) {
  command_
      ->add_option("study", study_path_,
                   "hand study YAML file, or its name in config/experiments (hand_contact: "
                   "config/experiments/hand_contact.yaml)")
      ->required()
      ->transform(named_config("experiments"))
      ->check(CLI::ExistingFile);
  command_->add_option("-o,--out", options_.out_dir,
                       "folder for the CSVs, the report and the figures (default: a new "
                       "folder in /tmp)");
  command_->add_option("--runs", options_.runs, "only these runs (comma-separated names)")->delimiter(',');
  command_->add_flag("--no-plots{false}", options_.plots, "no figures");
}

int HandStudyCommand::run() const {
  const experiment::HandStudyConfig config = experiment::load_hand_study(study_path_);
  const experiment::HandStudyResult result = experiment::run_hand_study(config, options_);
  std::printf("%s", experiment::format_hand_study_markdown(config, result.runs).c_str());
  std::printf("\nreport: %s\nMAD per joint: %s\nruns: %s\nsamples: %s\n", result.markdown.c_str(),
              result.mad_csv.c_str(), result.runs_csv.c_str(), result.trace_csv.c_str());
  if (!result.plot_error.empty()) std::printf("[hand-study] warning: no figures: %s\n", result.plot_error.c_str());
  const bool sound = std::all_of(result.runs.begin(), result.runs.end(),
                                 [](const experiment::HandStudyRunResult& r) { return r.sound(); });
  if (!sound) std::printf("RESULT: FAILED (a run had MuJoCo warnings or the fingertip left the panel, see Runs)\n");
  return sound ? 0 : 1;
}

}  // namespace teleop::cli
