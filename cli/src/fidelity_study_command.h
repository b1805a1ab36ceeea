#pragma once
// `teleop fidelity-study STUDY.yaml`: how good is the twin? The coupling thesis's accuracy study
// on the Panda-class arm (docs/fidelity.md): CSVs, a Markdown report in the shape of the thesis's
// Tables 4.1 and 4.2 with its numbers beside ours, and the error-over-time figures.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "teleop/experiment/fidelity_study.h"

namespace teleop::cli {

class FidelityStudyCommand {
 public:
  /// Adds the subcommand to `app`.
  explicit FidelityStudyCommand(CLI::App& app);

  bool parsed() const { return command_->parsed(); }
  /// Runs the study and prints its Markdown report and where the files are. Returns 0 when no
  /// simulation raised a MuJoCo warning, else 1. A bad study file throws ConfigError (main
  /// reports it).
  int run() const;

 private:
  CLI::App* command_;
  std::string study_path_;
  experiment::FidelityStudyOptions options_;
};

}  // namespace teleop::cli
