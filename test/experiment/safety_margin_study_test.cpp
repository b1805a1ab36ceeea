// PARTI §3.1, Fig. 5 (teleop fidelity-study safety_margins, docs/fidelity.md): the operated two-arm
// body driven hand against hand, its twin's margin spheres rendered back. The shipped study file's
// scenario, 3 s simulated per case.
#include "teleop/experiment/safety_margin_study.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::experiment {
namespace {

SafetyMarginScenario shipped() {
  return load_safety_margin_study(std::string(TELEOP_SOURCE_DIR) + "/config/experiments/safety_margins.yaml");
}

const SafetyMarginCase& case_named(const SafetyMarginScenario& s, const std::string& name) {
  for (const SafetyMarginCase& c : s.cases) {
    if (c.name == name) return c;
  }
  throw std::out_of_range(name);
}

TEST(TwinSafetyMargins, KeepTheArmsAndTheMarginsApartWhenActivatedBeforeTouch) {
  const SafetyMarginScenario s = shipped();
  const SafetyMarginResult r = run_safety_margin_case(s, case_named(s, "activation_25mm"), s.feedback_gain);
  RecordProperty("min_twin_margin_m", std::to_string(r.min_twin_margin_m));
  RecordProperty("min_physical_margin_m", std::to_string(r.min_physical_margin_m));
  RecordProperty("min_arms_m", std::to_string(r.min_arms_m));
  EXPECT_GE(r.first_contact_s, 0.0) << "the hands did come within the activation distance";
  EXPECT_GE(r.min_arms_m, 0.0) << "the arms' own geometry never touches";
  EXPECT_GE(r.min_twin_margin_m, 0.0) << "the twin's spheres (Fig. 5's distance) stay apart";
  EXPECT_GE(r.min_physical_margin_m, 0.0) << "and so do the spheres on the operated arm";
  EXPECT_LT(r.rest_physical_margin_m, 0.025) << "at rest, inside the activation distance: the margin acts";
  EXPECT_EQ(r.warnings, 0);
}

TEST(TwinSafetyMargins, AreCrossedByTheCouplingDeflectionWhenActivatedAtTouch) {
  const SafetyMarginScenario s = shipped();
  const SafetyMarginResult r = run_safety_margin_case(s, case_named(s, "touch"), s.feedback_gain);
  RecordProperty("min_physical_margin_m", std::to_string(r.min_physical_margin_m));
  RecordProperty("rest_physical_margin_m", std::to_string(r.rest_physical_margin_m));
  // measured before the activation distance existed: -21.7 mm at impact, -6.5 mm at rest
  EXPECT_LT(r.min_physical_margin_m, -0.01);
  EXPECT_GT(r.min_physical_margin_m, -0.03);
  EXPECT_LT(r.rest_physical_margin_m, -0.003);
  EXPECT_GE(r.min_twin_margin_m, -0.005) << "the twin's own spheres barely penetrate";
  EXPECT_GE(r.min_arms_m, 0.0) << "the arms' own geometry still never touches (the spheres are large)";
  EXPECT_EQ(r.warnings, 0);
}

TEST(TwinSafetyMargins, AreCrossedWithoutRendering) {
  const SafetyMarginScenario s = shipped();
  const SafetyMarginResult r = run_safety_margin_case(s, case_named(s, "activation_25mm"), 0.0);
  EXPECT_LT(r.min_physical_margin_m, -0.05) << "nothing keeps the operated hands apart but their own flanges";
}

TEST(TwinSafetyMargins, ReportsThePapersBoundBesideOurs) {
  SafetyMarginScenario s = shipped();
  s.duration_s = 0.2;
  s.rest_window_s = 0.1;
  std::vector<SafetyMarginResult> cases;
  for (const SafetyMarginCase& c : s.cases) cases.push_back(run_safety_margin_case(s, c, s.feedback_gain));
  const std::string md = format_safety_margin_markdown(s, cases);
  EXPECT_NE(md.find("PARTI Fig. 5"), std::string::npos);
  EXPECT_NE(md.find("| activation_25mm | 25.0 |"), std::string::npos) << md;
  EXPECT_EQ(cases.at(0).trace.t_s.size(), 40u) << "0.2 s every 5 ms";
}

}  // namespace
}  // namespace teleop::experiment
