#pragma once
// The stiff wall's experiment (config/experiments/stiff_wall.yaml) as a process test runs it: one
// architecture on `lan` to a results row, and the experiment with its scenarios written beside a
// follower of the test's own (another executable, another configuration), to compare a robot's
// row with the MuJoCo backend's.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "process_helpers.h"
#include "results_row.h"

namespace teleop::test {

/// Runs `architecture` of `experiment` on `lan` (reports under site.dir/tag) and reads its row.
inline ResultsRow run_stiff_wall(const ProcessSite& site, const std::string& experiment, const std::string& architecture,
                                 const std::string& tag) {
  using namespace std::chrono_literals;
  const std::string csv = site.dir + "/" + tag + ".csv";
  const ProcessResult r = run_process({bin("teleop"), "experiment", experiment, "--runs", architecture, "--profiles", "lan",
                                       "--report-dir", site.dir + "/" + tag, "--csv", csv, "--domain",
                                       std::to_string(site.domain), "--no-plots"},
                                      120s);
  EXPECT_EQ(r.exit_status, 0) << r.output;
  ::testing::Test::RecordProperty(tag, read_file(csv));
  return read_results_row(csv);
}

/// The stiff wall's experiment and scenarios written to site.dir with the follower started as
/// `executable --config config`; returns the experiment's path.
inline std::string stiff_wall_with_follower(const ProcessSite& site, const std::string& executable,
                                            const std::string& config) {
  for (const char* run : {"position_position", "pfc", "pfc_tdpa", "mmt", "pfc_tdpa_delta"}) {
    const std::string scenario = std::string("stiff_wall_") + run + ".yaml";
    std::string text = read_file(source("config/scenarios/" + scenario));
    const std::string node = "    executable: teleop_follower\n    config: follower\n";
    const size_t at = text.find(node);
    if (at == std::string::npos) throw std::runtime_error(scenario + " changed: update this test");
    text.replace(at, node.size(), "    executable: " + executable + "\n    config: " + config + "\n");
    write_file(site.dir + "/" + scenario, text);
  }
  std::string experiment = read_file(source("config/experiments/stiff_wall.yaml"));
  for (size_t at = experiment.find("../scenarios/"); at != std::string::npos; at = experiment.find("../scenarios/", at)) {
    experiment.erase(at, std::string("../scenarios/").size());
  }
  write_file(site.dir + "/stiff_wall.yaml", experiment);
  return site.dir + "/stiff_wall.yaml";
}

}  // namespace teleop::test
