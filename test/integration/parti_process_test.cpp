// PARTI's studies as a user runs them from the README (docs/fidelity.md): `teleop fidelity-study
// safety_margins` and `teleop fidelity-study parti_twin` by name, the shipped files. Their reports
// hold the rows docs/fidelity.md shows (the studies are deterministic), and their figures are
// drawn. About 8 s, most of it the figures.
#include <gtest/gtest.h>

#include "figure_check.h"
#include "process_helpers.h"
#include "teleop/experiment/plots.h"

namespace teleop::test {
namespace {

// a hang guard, not a speed limit: the shipped parti_twin study under ASan takes a minute, more
// on a loaded host; the ctest timeout (300 s) stays above it
constexpr std::chrono::seconds kStudyTimeout{280};

TEST(PartiStudyProcess, SafetyMarginsReproducesTheDocsTableAndDrawsFigFive) {
  const std::string dir = make_temp_dir();
  const ProcessResult r =
      run_process({bin("teleop"), "fidelity-study", "safety_margins", "-o", dir}, kStudyTimeout);
  ASSERT_EQ(r.exit_status, 0) << r.output;
  const std::string report = read_file(dir + "/safety_margins.md");
  // docs/fidelity.md "PARTI §3.1, Fig. 5", digit for digit
  EXPECT_NE(report.find("| touch | 0.0 | -1.4 | -0.0 | -21.6 | -6.5 | 133.8 | 0 |"), std::string::npos) << report;
  EXPECT_NE(report.find("| activation_25mm | 25.0 | 23.6 | 25.0 | 3.6 | 18.0 | 160.0 | 0 |"), std::string::npos)
      << report;
  EXPECT_NE(read_file(dir + "/safety_margins_trace.csv").find("case,activation_m,t_s,"), std::string::npos);
  expect_figures_drawn({dir + "/safety_margins_distance.png"});
}

TEST(PartiStudyProcess, TwinStudyReproducesTheDocsTablesAndDrawsItsFigures) {
  const std::string dir = make_temp_dir();
  const ProcessResult r =
      run_process({bin("teleop"), "fidelity-study", "parti_twin", "-o", dir}, kStudyTimeout);
  ASSERT_EQ(r.exit_status, 0) << r.output;
  const std::string report = read_file(dir + "/parti_twin.md");
  // docs/fidelity.md "PARTI §3.2", digit for digit
  EXPECT_NE(report.find("| static_contact | 0.895 (0.489–1.3) | 4.76 (2.65–8) | 2.73 (1.17–5.19) |"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("| momentum observer (eqs. 6-8) | 3.84 (2.7–5.86) | 24.4 (22.8–26.1) |"), std::string::npos)
      << report;
  EXPECT_NE(report.find("g(q) − τ_J | 10.8 (10–12.1) | 39.5 (37.4–43) |"), std::string::npos) << report;
  EXPECT_NE(read_file(dir + "/parti_twin_phases.csv").find("seed,phase,samples,"), std::string::npos);
  expect_figures_drawn({dir + "/parti_twin_errors.png", dir + "/parti_twin_estimators.png"});
}

}  // namespace
}  // namespace teleop::test
