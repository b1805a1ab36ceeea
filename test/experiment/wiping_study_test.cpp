// The wiping study (coupling thesis §4.4): the wiper's angle setter, a sweep of two cells in two
// workers (every wipe in contact on a high panel, none on a low one), and the report's tables.
#include "teleop/experiment/wiping_study.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sweep_parameters.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::experiment {
namespace {

std::string source(const std::string& path) { return std::string(TELEOP_SOURCE_DIR) + "/" + path; }

// the shipped study with short wipes: about 4 s simulated per cell
WipingStudyConfig short_study() {
  WipingStudyConfig c = load_wiping_study(source("config/experiments/wiping.yaml"));
  c.plan.reach_s = 1.0;
  c.plan.press_s = 0.3;
  c.plan.stroke_s = 0.5;
  c.plan.lift_s = 0.2;
  c.plan.shift_s = 0.3;
  c.plan.settle_s = 0.1;
  return c;
}

Eigen::Matrix3d site_rotation(const sim::MujocoModel& sim, const char* site) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(sim.data()->site_xmat + 9 * sim.site_id(site));
}

TEST(WipingStudy, AngleSetterTiltsTheWiperAboutTheFlangeX) {
  sim::MujocoModel sim = sim::MujocoModel::load(source("config/models/scene_wiping.xml"));
  for (double angle : {0.0, -0.15}) {
    apply_model_parameter({"a", "body_angle_x:wiper", {}}, angle, sim);
    sim.reset("ready");
    const Eigen::Matrix3d tool_in_hand = site_rotation(sim, "ee_site").transpose() * site_rotation(sim, "tool_site");
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
    EXPECT_TRUE(tool_in_hand.isApprox(expected, 1e-9)) << "angle " << angle << ":\n" << tool_in_hand;
  }
}

TEST(WipingStudy, CountsEveryWipeOnAHighPanelAndNoneOnALowOne) {
  WipingStudyConfig c = short_study();
  c.wiper_angle.values = {0.0};
  // 2 cm above the planned panel (the plan presses into it) and 5 cm below (out of reach)
  c.panel_height.values = {c.panel_height.planned + 0.02, c.panel_height.planned - 0.05};
  c.jobs = 2;
  const std::vector<WipingCell> cells = run_wiping_sweep(c);
  ASSERT_EQ(cells.size(), 2u);
  for (const WipingCell& cell : cells) {
    ASSERT_EQ(cell.error, "");
    EXPECT_EQ(cell.mujoco_warnings, 0);
    ASSERT_EQ(cell.wipes.size(), 3u);
  }
  EXPECT_EQ(cells[0].panel_height_m, c.panel_height.values[0]) << "cells come back in grid order";
  EXPECT_EQ(cells[0].contacts(), 3);
  EXPECT_EQ(cells[1].contacts(), 0);
  // the contact shows in the estimated external torque: above the free-motion level of either cell
  const double touched = cells[0].wipes[0].tau_ext_peak_nm.maxCoeff();
  EXPECT_GT(touched, 2.0 * cells[1].wipes[0].tau_ext_peak_nm.maxCoeff());
  EXPECT_GT(cells[0].wipes[0].peak_force_n, c.contact_force_n);
  EXPECT_EQ(cells[1].wipes[0].peak_force_n, 0.0);
}

TEST(WipingStudy, ReportPutsTheThesisTablesBesideOurs) {
  WipingStudyConfig c = short_study();
  c.wiper_angle.values = {0.0};
  c.panel_height.values = {0.3, 0.2};
  WipingCell touched;
  touched.wiper_angle_rad = 0.0;
  touched.panel_height_m = 0.3;
  touched.wipes.assign(3, WipeOutcome{});
  for (WipeOutcome& w : touched.wipes) {
    w.contact = true;
    w.tau_ext_peak_nm[0] = 4.25;
  }
  WipingCell missed = touched;
  missed.panel_height_m = 0.2;
  for (WipeOutcome& w : missed.wipes) w = WipeOutcome{};
  const std::string md = format_wiping_markdown(c, {touched, missed});
  EXPECT_NE(md.find("| 0.000 rad | 3/3 contacts | no contacts |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.0 rad | 2/3 contacts | 3/3 contacts | 3/3 contacts |"), std::string::npos) << md;
  EXPECT_NE(md.find("J0: 4.2/4.2/4.2 N m"), std::string::npos) << md;
  const std::string csv = format_wiping_csv({touched, missed});
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7) << "a header and one row per cell and wipe";
}

TEST(WipingStudyFile, RejectsASweptParameterThatDoesNotChangeTheModelNamingTheKey) {
  std::ifstream in(source("config/experiments/wiping.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "\"body_angle_x:wiper\"";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "press_depth_m");
  // the model by absolute path: the copy lives elsewhere
  yaml.replace(yaml.find("../models/"), 3, source("config/"));
  // one name per process: the sanitizer build's run of this test may run beside this one
  const std::string path =
      (std::filesystem::temp_directory_path() / ("wiping_study_test_bad_" + std::to_string(getpid()) + ".yaml"))
          .string();
  std::ofstream(path) << yaml;
  try {
    load_wiping_study(path);
    FAIL() << "accepted a parameter of the press scenario";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("wiping_study.wiper_angle.set"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace teleop::experiment
