#include "hand_study_paper.h"

namespace teleop::experiment {

// clang-format off
const std::array<PaperMadRow, 15>& paper_mad_rows() {
  // as printed: Table II's columns in units of 1e-3, 1e-4, 1e-4 rad, Table III's of 1e-15 rad
  static const std::array<PaperMadRow, 15> rows = {{
      {"Finger_Spread",          {0.0240e-3, 0.01541e-4, 0.00111e-4}, 0.0},
      {"Index_Finger_Distal",    {0.0097e-3, 0.00091e-4, 0.00141e-4}, 0.0},
      {"Index_Finger_Proximal",  {0.0204e-3, 0.00151e-4, 0.00161e-4}, 0.0},
      {"Middle_Finger_Distal",   {0.0072e-3, 0.00171e-4, 0.01111e-4}, 0.0354e-15},
      {"Middle_Finger_Proximal", {0.0196e-3, 0.03041e-4, 0.03261e-4}, 0.0555e-15},
      {"Pinky",                  {0.0222e-3, 0.02871e-4, 0.03111e-4}, 0.0330e-15},
      {"Ring_Finger",            {0.0221e-3, 0.03011e-4, 0.03121e-4}, 0.0},
      {"Thumb_Flexion",          {0.0471e-3, 0.01221e-4, 0.00331e-4}, 0.0},
      {"Thumb_Opposition",       {0.4379e-3, 0.05771e-4, 0.00531e-4}, 0.0},
      {"shoulder_lift_joint",    {0.0151e-3, 0.10011e-4, 0.12251e-4}, 0.0422e-15},
      {"shoulder_pan_joint",     {0.0149e-3, 0.02301e-4, 0.01531e-4}, 0.0845e-15},
      {"elbow_joint",            {0.0173e-3, 0.15331e-4, 0.17551e-4}, 0.1082e-15},
      {"wrist_1_joint",          {0.0474e-3, 0.34761e-4, 0.38181e-4}, 0.1400e-15},
      {"wrist_2_joint",          {0.0603e-3, 0.00921e-4, 0.01131e-4}, 0.1561e-15},
      {"wrist_3_joint",          {0.0118e-3, 0.06101e-4, 0.04361e-4}, 0.0001e-15},
  }};
  return rows;
}

const PaperMadRow& paper_mad_average() {
  static const PaperMadRow average = {"Average", {5.1799e-05, 5.8178e-06, 5.7914e-06}, 4.3664e-17};
  return average;
}
// clang-format on

}  // namespace teleop::experiment
