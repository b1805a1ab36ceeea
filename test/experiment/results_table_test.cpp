// The repeats of an experiment summed up: each run x profile's ok repeats give a mean and a sample
// standard deviation per metric (known values here); a repeat that is not ok counts in neither.
#include "teleop/experiment/results_table.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace teleop::experiment {
namespace {

RunRow row(const std::string& run, const std::string& profile, int repeat, const std::string& status, double felt_n,
           bool stable) {
  RunRow r;
  r.run = run;
  r.profile = profile;
  r.repeat = repeat;
  r.seed = 6 + static_cast<uint64_t>(repeat);
  r.status = status;
  r.metrics.force_felt_n = felt_n;
  r.metrics.mad_rad = 1e-5;
  r.verdict.stable = stable;
  return r;
}

// the line of `text` that starts with `start`
std::string line_of(const std::string& text, const std::string& start) {
  const size_t at = text.find("\n" + start);
  if (at == std::string::npos) return "";
  return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
}

const std::vector<RunRow> kRows{row("mmt", "lan", 1, "ok", 10.0, true),          row("mmt", "lan", 2, "ok", 12.0, true),
                                row("mmt", "lan", 3, "ok", 14.0, false),         row("pfc", "lan", 1, "ok", 3.0, true),
                                row("pfc", "lan", 2, "invalid", 99.0, true),     row("pfc", "lan", 3, "ok", 5.0, true)};

TEST(ResultsTable, EachRepeatIsARowWithItsSeed) {
  const std::string csv = format_csv(kRows, AnalysedTask::kStiffWall);
  EXPECT_EQ(csv.rfind("run,profile,repeat,seed,status,stable,stable_why,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\nmmt,lan,2,8,ok,yes,"), std::string::npos) << csv;
  const std::string table = format_table(kRows, "t", AnalysedTask::kStiffWall);
  EXPECT_EQ(line_of(table, "pfc").find("lan r1"), 18u) << table;
  EXPECT_NE(table.find("lan r3"), std::string::npos) << table;
}

TEST(ResultsTable, TheSummaryGivesMeanAndSampleSpreadOverTheOkRepeats) {
  const std::string csv = format_summary_csv(kRows, AnalysedTask::kStiffWall);
  EXPECT_EQ(csv.rfind("run,profile,repeats,ok,stable,force_error_n_mean,force_error_n_sd,", 0), 0u) << csv;
  // mmt: 10, 12, 14 N: mean 12, sd 2; two of three stable
  const std::string mmt = line_of(csv, "mmt,");
  EXPECT_EQ(mmt.rfind("mmt,lan,3,3,2,,,12,2,", 0), 0u) << csv;
  // pfc: the invalid repeat's 99 N counts in neither: 3 and 5 N, mean 4, sd sqrt(2)
  const std::string pfc = line_of(csv, "pfc,");
  EXPECT_EQ(pfc.rfind("pfc,lan,3,2,2,,,4,1.41421356,", 0), 0u) << csv;
  const std::string table = format_summary_table(kRows, AnalysedTask::kStiffWall);
  EXPECT_NE(line_of(table, "mmt").find("12±2"), std::string::npos) << table;
  EXPECT_NE(line_of(table, "pfc").find("2/3"), std::string::npos) << table;
}

TEST(ResultsTable, TheSummaryGoesBesideTheCsv) {
  EXPECT_EQ(summary_csv_path("/tmp/r/stiff_wall.csv"), "/tmp/r/stiff_wall_summary.csv");
  EXPECT_EQ(summary_csv_path("out"), "out_summary.csv");
}

}  // namespace
}  // namespace teleop::experiment
