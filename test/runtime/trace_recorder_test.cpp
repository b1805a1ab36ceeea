// TraceRecorder: preallocated rows, ring wrap, CSV format (time columns, state names); the
// NodeLogic trace hooks.
#include "teleop/runtime/trace_recorder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "allocation_counter.h"
#include "teleop/runtime/node_logic.h"
#include "test_helpers.h"

namespace teleop::runtime {
namespace {

// a row at `t_ns` on the monotonic clock, on time
TraceTime at(int64_t t_ns) { return {t_ns, 0, 0}; }

TEST(TraceRecorder, WritesHeaderTimesAndValuesWhenNotFull) {
  TraceRecorder r({"a", "b"}, 10);
  double* row = r.begin_row({1'500'000'001, 1'718'000'000'123'456'789, 12'345});
  row[0] = 1.25;
  row[1] = -3e-7;
  row = r.begin_row({2'000'000'000, 1'718'000'000'623'456'790, 7});
  row[0] = 1.0 / 3.0;
  test::TempDir dir("trace_recorder");
  r.write_csv(dir.path("t.csv"));
  // the wall time to the nanosecond (a double would lose the last digits), the lateness in us
  EXPECT_EQ(test::read_text(dir.path("t.csv")),
            "t_s,wall_s,lateness_us,a,b\n"
            "1.500000001,1718000000.123456789,12.345,1.25,-3e-07\n"
            "2.000000000,1718000000.623456790,0.007,0.333333333,nan\n");
  EXPECT_EQ(r.rows(), 2u);
  EXPECT_EQ(r.rows_dropped(), 0u);
}

TEST(TraceRecorder, KeepsTheMostRecentRowsAndCountsTheOverwrittenWhenTheRingWraps) {
  TraceRecorder r({"v"}, 3);
  for (int i = 0; i < 5; ++i) r.begin_row(at(int64_t{i} * 1'000'000'000))[0] = i;
  EXPECT_EQ(r.rows(), 3u);
  EXPECT_EQ(r.rows_dropped(), 2u);
  test::TempDir dir("trace_recorder_wrap");
  r.write_csv(dir.path("t.csv"));
  EXPECT_EQ(test::read_text(dir.path("t.csv")),
            "t_s,wall_s,lateness_us,v\n2.000000000,0.000000000,0.000,2\n3.000000000,0.000000000,0.000,3\n"
            "4.000000000,0.000000000,0.000,4\n");
}

TEST(TraceRecorder, WritesStateColumnsAsTheStatesNamesAndOtherValuesAsNumbers) {
  TraceRecorder r({"state", "left_state", "statex", "n"}, 4);
  double* row = r.begin_row(at(0));
  row[0] = static_cast<double>(msg::STATE_RUNNING);
  row[1] = static_cast<double>(msg::STATE_SAFE_HOLD);
  row[2] = static_cast<double>(msg::STATE_RUNNING);  // not a state column: stays a number
  row[3] = 3.0;
  row = r.begin_row(at(1'000'000));
  row[0] = static_cast<double>(msg::STATE_FAULT);
  row[1] = 2.5;  // names no state: written as it is; the last column unset
  test::TempDir dir("trace_recorder_states");
  r.write_csv(dir.path("t.csv"));
  EXPECT_EQ(test::read_text(dir.path("t.csv")),
            "t_s,wall_s,lateness_us,state,left_state,statex,n\n"
            "0.000000000,0.000000000,0.000,running,safe_hold,1,3\n"
            "0.001000000,0.000000000,0.000,fault,2.5,nan,nan\n");
}

TEST(TraceRecorder, WritesALateCycleAndTimesBeforeTheEpochWithTheirSign) {
  TraceRecorder r({"v"}, 1);
  r.begin_row({-1'500'000'000, -2, -1'250})[0] = 1.0;
  test::TempDir dir("trace_recorder_sign");
  r.write_csv(dir.path("t.csv"));
  EXPECT_EQ(test::read_text(dir.path("t.csv")), "t_s,wall_s,lateness_us,v\n-1.500000000,-0.000000002,-1.250,1\n");
}

TEST(TraceRecorder, KnowsAStateColumnByItsName) {
  EXPECT_TRUE(is_state_column("state"));
  EXPECT_TRUE(is_state_column("left_state"));
  EXPECT_FALSE(is_state_column("_state"));
  EXPECT_FALSE(is_state_column("states"));
  EXPECT_FALSE(is_state_column("statex"));
  EXPECT_FALSE(is_state_column("t_s"));
}

TEST(TraceRecorder, PresetsEveryValueToNanSoUnfilledColumnsShowAsMissing) {
  TraceRecorder r({"a", "b", "c"}, 2);
  r.begin_row(at(0))[1] = 7.0;
  r.begin_row(at(1));
  double* row = r.begin_row(at(2));  // reuses the first slot: old values must not leak through
  EXPECT_TRUE(std::isnan(row[0]));
  EXPECT_TRUE(std::isnan(row[1]));
  EXPECT_TRUE(std::isnan(row[2]));
}

TEST(TraceRecorder, DoesNotAllocateWhenRecordingIncludingAcrossTheWrap) {
  TraceRecorder r({"a", "b", "c", "d"}, 100);
  test::ScopedAllocationCounter allocations;
  for (int i = 0; i < 1000; ++i) {
    double* row = r.begin_row(at(i));
    for (int c = 0; c < 4; ++c) row[c] = i * c;
  }
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(r.rows_dropped(), 900u);
}

TEST(TraceRecorder, RefusesZeroCapacityAndReportsAnUnwritableFile) {
  EXPECT_THROW(TraceRecorder({"a"}, 0), std::invalid_argument);
  TraceRecorder r({"a"}, 1);
  EXPECT_NE(test::error_of<std::runtime_error>([&] {
              r.write_csv("/nonexistent/dir/t.csv");
            }).find("cannot write the trace /nonexistent/dir/t.csv"),
            std::string::npos);
}

// a logic that traces its cycle index and twice it
class TracedLogic : public NodeLogic {
 public:
  void cycle(const CycleTick& tick) override { index_ = static_cast<double>(tick.index); }
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(NodeReport&) const override {}
  void trace_columns(std::vector<std::string>& columns) const override { columns = {"index", "twice"}; }
  void trace_row(double* row) const override {
    row[0] = index_;
    row[1] = 2 * index_;
  }

 private:
  double index_ = 0;
};

class UntracedLogic : public NodeLogic {
 public:
  void cycle(const CycleTick&) override {}
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(NodeReport&) const override {}
};

TEST(NodeLogicTrace, HasNoColumnsByDefault) {
  UntracedLogic logic;
  std::vector<std::string> columns;
  logic.trace_columns(columns);
  EXPECT_TRUE(columns.empty());
}

TEST(NodeLogicTrace, RecordsOneRowPerCycleWithoutAllocatingWhenDrivenLikeTheRunner) {
  TracedLogic logic;
  std::vector<std::string> columns;
  logic.trace_columns(columns);
  TraceRecorder trace(columns, 10);
  {
    test::ScopedAllocationCounter allocations;
    for (uint64_t i = 0; i < 3; ++i) {
      const CycleTick tick{i, static_cast<int64_t>(i) * 1'000'000, static_cast<int64_t>(i) * 1'000'000 + 5};
      logic.cycle(tick);
      logic.trace_row(trace.begin_row({tick.now_ns, 0, tick.now_ns - tick.deadline_ns}));
    }
    EXPECT_EQ(allocations.count(), 0u);
  }
  test::TempDir dir("trace_logic");
  trace.write_csv(dir.path("t.csv"));
  EXPECT_EQ(test::read_text(dir.path("t.csv")),
            "t_s,wall_s,lateness_us,index,twice\n0.000000005,0.000000000,0.005,0,0\n"
            "0.001000005,0.000000000,0.005,1,2\n0.002000005,0.000000000,0.005,2,4\n");
}

}  // namespace
}  // namespace teleop::runtime
