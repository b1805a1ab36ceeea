#pragma once
// The study and plot tests' check of their figures: every PNG exists, and png_check.py
// (python3-matplotlib) opens it and finds the size scripts/teleop_plot/figure_style.py draws and
// a plot area that shows data.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "process_helpers.h"
#include "teleop/experiment/plots.h"

namespace teleop::test {

inline void expect_figures_drawn(const std::vector<std::string>& files) {
  for (const std::string& f : files) EXPECT_TRUE(std::filesystem::exists(f)) << f;
  // figure_style.py: 1200 x 800 pixels; a drawn plot is more than 10 kB
  std::vector<std::string> argv = {"/usr/bin/env", experiment::find_plot_tool().python, "-B",
                                   source("test/integration/png_check.py"), "1200", "800", "10000"};
  argv.insert(argv.end(), files.begin(), files.end());
  const ProcessResult r = run_process(argv, std::chrono::seconds(60));
  EXPECT_EQ(r.exit_status, 0) << r.output;
}

}  // namespace teleop::test
