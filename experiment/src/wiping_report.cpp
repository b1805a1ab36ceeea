// The wiping study's report: Tables 4.3 and 4.4 of the coupling thesis in shape with the thesis's
// own beside them, the per-joint peaks of every cell, and the CSV of every wipe.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "report_files.h"
#include "teleop/experiment/wiping_study.h"

namespace teleop::experiment {
namespace {

// The thesis's grid (§4.4.1) and results (§4.4.2), in its order: rows are the wiper x-angles
// 0.0, -0.075, -0.15 rad, columns the panel heights 1.00, 1.02, 1.04 m.
constexpr std::array<const char*, 3> kThesisAngles = {"0.0", "-0.075", "-0.15"};
constexpr std::array<const char*, 3> kThesisHeights = {"1.00 m", "1.02 m", "1.04 m"};
// Table 4.3: wipes in contact (of 3)
constexpr std::array<std::array<int, 3>, 3> kTable43 = {{{2, 3, 3}, {0, 3, 3}, {0, 0, 3}}};
// Table 4.4: the simulated peaks against the real robot's (its words, shortened)
constexpr std::array<std::array<const char*, 3>, 3> kTable44 = {{
    {"J0: 50% smaller, J3: 50% larger on the 2nd contact", "J0: 50% larger peak, J3: 4 x as large",
     "J0: > 2 x as large, J3: 5 x as large"},
    {"no contacts", "J0: 50% smaller, J3: 50% larger on the 2nd contact", "J0: 2-4 N m larger, J3: up to 4 x as large"},
    {"no contacts", "no contacts", "J0: 50% smaller, J3: 50% larger on the 2nd contact"},
}};
// §4.4.2: the real robot's external-torque peaks per contact [N m], joints 0 and 3
constexpr std::array<double, 3> kRealJ0 = {14, 12, 8};
constexpr std::array<double, 3> kRealJ3 = {8, 8, 6};

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

const WipingCell* find(const std::vector<WipingCell>& cells, double angle, double height) {
  for (const WipingCell& c : cells) {
    if (c.wiper_angle_rad == angle && c.panel_height_m == height) return &c;
  }
  return nullptr;
}

std::string contacts_text(const WipingCell& c) {
  if (!c.error.empty()) return "failed";
  const int n = c.contacts();
  return n == 0 ? "no contacts" : std::to_string(n) + "/" + std::to_string(c.wipes.size()) + " contacts";
}

// one joint's peak in each wipe that touched ("–" for one that did not)
std::string per_wipe(const WipingCell& c, int joint) {
  std::string s;
  for (size_t i = 0; i < c.wipes.size(); ++i) {
    if (i > 0) s += "/";
    s += c.wipes[i].contact ? fixed(c.wipes[i].tau_ext_peak_nm[joint], 1) : "–";
  }
  return s;
}

std::string peaks_text(const WipingCell& c) {
  if (!c.error.empty()) return "failed: " + c.error;
  if (c.contacts() == 0) return "no contacts";
  return "J0: " + per_wipe(c, 0) + " N m, J3: " + per_wipe(c, 3) + " N m";
}

template <typename Cell>
void grid_table(std::ostringstream& o, const WipingStudyConfig& config, const std::vector<WipingCell>& cells,
                Cell cell) {
  o << "| wiper x-angle \\ panel height |";
  for (double h : config.panel_height.values) o << ' ' << fixed(h, 3) << " m |";
  o << "\n|---|";
  for (size_t i = 0; i < config.panel_height.values.size(); ++i) o << "---|";
  o << '\n';
  for (double a : config.wiper_angle.values) {
    o << "| " << fixed(a, 3) << " rad |";
    for (double h : config.panel_height.values) {
      const WipingCell* c = find(cells, a, h);
      o << ' ' << (c != nullptr ? cell(*c) : std::string("–")) << " |";
    }
    o << '\n';
  }
}

template <typename Cell>
void thesis_table(std::ostringstream& o, Cell cell) {
  o << "| wiper x-angle \\ panel height |";
  for (const char* h : kThesisHeights) o << ' ' << h << " |";
  o << "\n|---|---|---|---|\n";
  for (size_t a = 0; a < kThesisAngles.size(); ++a) {
    o << "| " << kThesisAngles[a] << " rad |";
    for (size_t h = 0; h < kThesisHeights.size(); ++h) o << ' ' << cell(a, h) << " |";
    o << '\n';
  }
}

}  // namespace

std::string format_wiping_csv(const std::vector<WipingCell>& cells) {
  std::ostringstream o;
  o.precision(10);
  o << "wiper_angle_rad,panel_height_m,wipe,contact,contact_steps,peak_force_n,mean_force_n";
  for (const char* kind : {"tau_ext_peak", "constraint_peak", "free_tau_ext_peak"}) {
    for (int j = 0; j < control::kDof; ++j) o << ',' << kind << "_j" << j << "_nm";
  }
  o << ",mujoco_warnings,error\n";
  for (const WipingCell& c : cells) {
    for (size_t i = 0; i < std::max<size_t>(1, c.wipes.size()); ++i) {
      const WipeOutcome w = i < c.wipes.size() ? c.wipes[i] : WipeOutcome{};
      o << c.wiper_angle_rad << ',' << c.panel_height_m << ',' << i + 1 << ',' << (w.contact ? 1 : 0) << ','
        << w.contact_steps << ',' << w.peak_force_n << ',' << w.mean_force_n;
      for (const control::JointVector* v : {&w.tau_ext_peak_nm, &w.constraint_peak_nm, &c.free_tau_ext_peak_nm}) {
        for (int j = 0; j < control::kDof; ++j) o << ',' << (*v)[j];
      }
      o << ',' << c.mujoco_warnings << ',' << csv_quoted(c.error) << '\n';
    }
  }
  return o.str();
}

std::string format_wiping_markdown(const WipingStudyConfig& config, const std::vector<WipingCell>& cells) {
  std::ostringstream o;
  const size_t wipes = config.plan.press_depth_m.size();
  o << "# Wiping study `" << config.name << "`: coupling thesis §4.4, Tables 4.3 and 4.4\n\n"
    << "The plan assumes a wiper x-angle of " << fixed(config.wiper_angle.planned, 3) << " rad and a panel at "
    << fixed(config.panel_height.planned, 3) << " m; " << wipes
    << " wipes under Cartesian impedance; joints zero-indexed as in the thesis (J0 = the base joint).\n\n"
    << "## Wipes in contact with the panel (Table 4.3's shape)\n\nOurs (" << config.panel_height.name << " = the "
    << "panel's centre height in scene_wiping.xml):\n\n";
  grid_table(o, config, cells, contacts_text);
  o << "\nThe thesis's (Rollin' Justin, panel heights in its world):\n\n";
  thesis_table(o, [](size_t a, size_t h) {
    return kTable43[a][h] == 0 ? std::string("no contacts") : std::to_string(kTable43[a][h]) + "/3 contacts";
  });
  o << "\n## External-torque peaks (Table 4.4's shape)\n\nOurs: per wipe in contact, the peak |tau_ext| of "
       "J0 and J3 (the momentum observer's estimate, K_O = "
    << fixed(config.observer_gain_per_s, 0) << " 1/s):\n\n";
  grid_table(o, config, cells, peaks_text);
  o << "\nThe thesis's, relative to the real robot's peaks (J0: " << fixed(kRealJ0[0], 0) << '/' << fixed(kRealJ0[1], 0)
    << '/' << fixed(kRealJ0[2], 0) << " N m, J3: " << fixed(kRealJ3[0], 0) << '/' << fixed(kRealJ3[1], 0) << '/'
    << fixed(kRealJ3[2], 0) << " N m for its three contacts):\n\n";
  thesis_table(o, [](size_t a, size_t h) { return std::string(kTable44[a][h]); });
  o << "\n## Every joint (peak over the wipes) [N m]\n\nThe mean contact force: of the wipe that pressed "
       "hardest, over its steps in contact. Free motion: the largest |tau_ext| of any joint outside the wipes "
       "(the estimate's level without contact).\n\n"
    << "| x-angle [rad] | height [m] | contacts | mean contact force [N] |";
  for (int j = 0; j < control::kDof; ++j) o << " J" << j << " |";
  o << " free motion, max joint | warnings |\n|---|---|---|---|";
  for (int j = 0; j < control::kDof; ++j) o << "---|";
  o << "---|---|\n";
  for (const WipingCell& c : cells) {
    control::JointVector peak = control::JointVector::Zero();
    double force = 0.0;
    for (const WipeOutcome& w : c.wipes) {
      peak = peak.cwiseMax(w.tau_ext_peak_nm);
      force = std::max(force, w.mean_force_n);
    }
    o << "| " << fixed(c.wiper_angle_rad, 3) << " | " << fixed(c.panel_height_m, 3) << " | " << contacts_text(c)
      << " | " << fixed(force, 1) << " |";
    for (int j = 0; j < control::kDof; ++j) o << ' ' << fixed(peak[j], 1) << " |";
    o << ' ' << fixed(c.free_tau_ext_peak_nm.maxCoeff(), 2) << " | " << c.mujoco_warnings << " |\n";
  }
  return o.str();
}

}  // namespace teleop::experiment
