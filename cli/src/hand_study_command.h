#pragma once
// `teleop hand-study STUDY.yaml`: the SVH hand study reproduced in MuJoCo (docs/hand.md): CSVs,
// a Markdown table beside the paper's Tables II and III, and the tip-force figure.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "teleop/experiment/hand_study.h"

namespace teleop::cli {

class HandStudyCommand {
 public:
  /// Adds the subcommand to `app`.
  explicit HandStudyCommand(CLI::App& app);

  bool parsed() const { return command_->parsed(); }
  /// Runs the study and prints its Markdown report and where the files are. Returns 0 when every
  /// run was sound (no MuJoCo warning, the fingertip pressing throughout the recording), else 1.
  /// A bad study file throws ConfigError (main reports it).
  int run() const;

 private:
  CLI::App* command_;
  std::string study_path_;
  experiment::HandStudyOptions options_;
};

}  // namespace teleop::cli
