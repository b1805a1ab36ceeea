#pragma once
// The numbers the SVH study reports (shared/papers/svh-hand-gazebo-mujoco.md): the MAD of each
// joint at rest in contact, Table II (Gazebo, three finger-link inertias) and Table III (MuJoCo,
// 0.1 kg m^2), for the report to set ours beside them.

#include <array>
#include <string_view>

namespace teleop::experiment {

struct PaperMadRow {
  std::string_view joint;
  std::array<double, 3> gazebo_rad;  ///< at 0.001, 0.01, 0.1 kg m^2 (Table II)
  double mujoco_rad;                 ///< at 0.1 kg m^2 (Table III)
};

/// The 15 rows of Tables II and III, in their order (the order of hand_study_joints()).
const std::array<PaperMadRow, 15>& paper_mad_rows();
/// The tables' "Average" row.
const PaperMadRow& paper_mad_average();
/// The inertias of Table II's columns [kg m^2].
constexpr std::array<double, 3> kPaperInertiasKgm2 = {0.001, 0.01, 0.1};

}  // namespace teleop::experiment
