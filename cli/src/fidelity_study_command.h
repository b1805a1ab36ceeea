#pragma once
// `teleop fidelity-study STUDY.yaml`: how good is the twin? The coupling thesis's studies on the
// Panda-class arm (docs/fidelity.md), each writing CSVs, a Markdown report with the thesis's
// numbers beside ours, and figures: the accuracy study (a `fidelity_study:` file, Tables 4.1 and
// 4.2) and the wiping study (a `wiping_study:` file, Tables 4.3 and 4.4).

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "teleop/experiment/fidelity_study.h"
#include "teleop/experiment/wiping_study.h"

namespace teleop::cli {

class FidelityStudyCommand {
 public:
  /// Adds the subcommand to `app`.
  explicit FidelityStudyCommand(CLI::App& app);

  bool parsed() const { return command_->parsed(); }
  /// Runs the study and prints its Markdown report and where the files are. Returns 0 when no
  /// simulation raised a MuJoCo warning (nor failed), else 1. A bad study file throws
  /// ConfigError (main reports it).
  int run() const;

 private:
  int run_accuracy() const;
  int run_wiping() const;

  CLI::App* command_;
  std::string study_path_;
  experiment::FidelityStudyOptions options_;
  int jobs_ = 0;
};

}  // namespace teleop::cli
