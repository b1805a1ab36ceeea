// Reading trace CSVs: what TraceRecorder writes, and clear errors for broken files.
#include "teleop/experiment/trace.h"

#include <gtest/gtest.h>

#include <cmath>

#include "teleop/runtime/status_names.h"
#include "teleop/runtime/trace_recorder.h"
#include "test_helpers.h"

namespace teleop::experiment {
namespace {

std::string error_of(const std::function<void()>& f) { return test::error_of<TraceError>(f); }

TEST(ReadTrace, ReadsWhatTheRecorderWrites) {
  runtime::TraceRecorder recorder({"q_0", "q_1", "w"}, 10);
  double* row = recorder.begin_row({12'345'678'901'234, 1'718'000'000'123'456'789, 250'000});
  row[0] = 0.125;
  row[1] = -1e-9;
  row[2] = -1.88048943e-308;  // subnormal: a filtered signal decaying towards 0
  recorder.begin_row({12'345'679'901'234, 1'718'000'001'123'456'789, 0})[0] = 2.0;  // the rest NaN
  test::TempDir dir("read_trace");
  recorder.write_csv(dir.path("t.csv"));
  const Trace t = read_trace(dir.path("t.csv"));
  ASSERT_EQ(t.t_s.size(), 2u);
  EXPECT_DOUBLE_EQ(t.t_s[0], 12345.678901234);
  EXPECT_DOUBLE_EQ(t.column("wall_s")[0], 1718000000.123456789);
  EXPECT_DOUBLE_EQ(t.column("lateness_us")[0], 250.0);
  EXPECT_DOUBLE_EQ(t.column("q_0")[0], 0.125);
  EXPECT_DOUBLE_EQ(t.column("q_1")[0], -1e-9);
  EXPECT_DOUBLE_EQ(t.column("w")[0], -1.88048943e-308);
  EXPECT_DOUBLE_EQ(t.column("q_0")[1], 2.0);
  EXPECT_TRUE(std::isnan(t.column("w")[1]));
  EXPECT_EQ(t.numbered("q_").size(), 2u);
}

TEST(ReadTrace, ReadsTheStatesTheRecorderNamesAsTheirNumbers) {
  runtime::TraceRecorder recorder({"state", "right_state"}, 10);
  double* row = recorder.begin_row({1'000'000'000, 0, 0});
  row[0] = static_cast<double>(msg::STATE_SAFE_HOLD);
  row[1] = static_cast<double>(msg::STATE_STOPPING);
  test::TempDir dir("read_trace_states");
  recorder.write_csv(dir.path("t.csv"));
  const Trace t = read_trace(dir.path("t.csv"));
  EXPECT_EQ(t.column("state")[0], static_cast<double>(msg::STATE_SAFE_HOLD));
  EXPECT_EQ(t.column("right_state")[0], static_cast<double>(msg::STATE_STOPPING));
}

TEST(ReadTrace, StillReadsATraceOfNumericStatesWithoutTimeColumns) {
  test::TempDir dir("read_trace_old");
  const Trace t = read_trace(dir.write("old.csv", "t_s,state,left_state\n1.5,1,2\n2.5,running,\n"));
  EXPECT_EQ(t.column("state"), (std::vector<double>{1.0, static_cast<double>(msg::STATE_RUNNING)}));
  EXPECT_EQ(t.column("left_state")[0], 2.0);
  EXPECT_TRUE(std::isnan(t.column("left_state")[1]));
  EXPECT_FALSE(t.has("wall_s"));
}

TEST(ReadTrace, NamesTheFileAndColumnWhenAColumnIsMissing) {
  test::TempDir dir("read_trace_column");
  const Trace t = read_trace(dir.write("leader.csv", "t_s,a\n1,2\n"));
  EXPECT_EQ(error_of([&] { t.column("x_cmd_x"); }), dir.path("leader.csv") + ": no column 'x_cmd_x'");
  EXPECT_EQ(error_of([&] { t.numbered("q_"); }), dir.path("leader.csv") + ": no column 'q_0'");
}

// a node SIGKILLed while streaming its trace leaves half a row without a newline (seen in a soak
// under ASan): the finished rows are the trace
TEST(ReadTrace, LeavesOutTheUnfinishedRowOfAKilledWriter) {
  test::TempDir dir("read_trace_killed");
  const Trace t = read_trace(dir.write("k.csv", "t_s,a,b\n1,2,3\n2,4,6\n3,8"));
  ASSERT_EQ(t.t_s.size(), 2u);
  EXPECT_EQ(t.t_s.back(), 2.0);
  EXPECT_EQ(t.column("b").back(), 6.0);
  EXPECT_EQ(read_trace(dir.write("h.csv", "t_s,a\n1,2")).t_s.size(), 0u) << "a cut first row";
}

TEST(ReadTrace, NamesTheFileAndLineOfBrokenContent) {
  test::TempDir dir("read_trace_bad");
  EXPECT_NE(error_of([&] { read_trace(dir.path("absent.csv")); }).find(dir.path("absent.csv") + ": cannot open"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { read_trace(dir.write("e.csv", "")); }),
            dir.path("e.csv") + ": empty file, expected a header 't_s,<columns>'");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("h.csv", "time,a\n")); }),
            dir.path("h.csv") + ":1: the first column must be 't_s', got 'time'");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("n.csv", "t_s,a\n1,2\n2\n")); }),
            dir.path("n.csv") + ":3: 1 cells, the header has 2");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("v.csv", "t_s,a\n1,2x\n")); }),
            dir.path("v.csv") + ":2: a: '2x' is not a number");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("o.csv", "t_s,a\n1,1e999\n")); }),
            dir.path("o.csv") + ":2: a: '1e999' is not a number");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("s.csv", "t_s,state,a\n1,runing,running\n")); }),
            dir.path("s.csv") + ":2: state: 'runing' is not a number nor a state's name");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("a.csv", "t_s,a\n1,running\n")); }),
            dir.path("a.csv") + ":2: a: 'running' is not a number");
  EXPECT_EQ(error_of([&] { read_trace(dir.write("t.csv", "t_s,a\nnan,1\n")); }),
            dir.path("t.csv") + ":2: t_s: 'nan' is not a time");
}

}  // namespace
}  // namespace teleop::experiment
