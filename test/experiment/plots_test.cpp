// Finding a run's traces for its figures: a folder without any is an error naming it (no python
// involved: the figures themselves are test/integration/plot_process_test.cpp's).
#include "teleop/experiment/plots.h"

#include <gtest/gtest.h>

#include "test_helpers.h"

namespace teleop::experiment {
namespace {

std::string error_of(const std::function<void()>& f) { return test::error_of<PlotError>(f); }

TEST(RunTraces, FindsTheCsvFilesThatAreTracesSorted) {
  test::TempDir dir("plots_traces");
  dir.write("leader.csv", "t_s,wall_s,lateness_us,state\n1.0,2.0,3.0,running\n");
  dir.write("follower.csv", "t_s,x_x\n");
  dir.write("results.csv", "run,profile,status\n");  // an experiment's table: not a trace
  dir.write("leader.yaml", "t_s,\n");
  EXPECT_EQ(run_traces(dir.path("")), (std::vector<std::string>{dir.path("follower.csv"), dir.path("leader.csv")}));
}

TEST(RunTraces, ARunDirWithoutTracesIsAnErrorNamingTheDir) {
  test::TempDir dir("plots_no_traces");
  dir.write("tiny.csv", "run,profile,status\n");
  dir.write("leader.yaml", "name: leader\n");
  const std::string message = error_of([&] { run_traces(dir.path("")); });
  const std::string expected =
      dir.path("") + ": no trace in this directory (expected <node>.csv files with a t_s column";
  EXPECT_EQ(message.rfind(expected, 0), 0u) << message;
}

TEST(RunTraces, AMissingDirIsAnErrorNamingIt) {
  EXPECT_EQ(error_of([] { run_traces("/nonexistent/run"); }), "/nonexistent/run: no such directory");
}

}  // namespace
}  // namespace teleop::experiment
