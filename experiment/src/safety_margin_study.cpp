// PARTI Fig. 5's scenario: the operated two-arm body, its twin with margin spheres, the rendering.
#include "teleop/experiment/safety_margin_study.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "teleop/common/lowpass.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::experiment {
namespace {

constexpr const char* kSides[] = {"left", "right"};
// the arms' own geometry that can meet when the hands are driven together: wrist, hand, flange
constexpr const char* kNearLinks[] = {"link5", "link6", "link7"};

twin::TwinModelConfig physical_config(const SafetyMarginScenario& s) {
  twin::TwinModelConfig c;
  c.model_path = s.model_path;
  c.keyframe = s.keyframe;
  for (const char* left : kNearLinks) {
    for (const char* right : kNearLinks) {
      c.distance_pairs.push_back({std::string("left_") + left + "_right_" + right, std::string("body:left_") + left,
                                  std::string("body:right_") + right});
    }
  }
  return c;
}

twin::TwinModelConfig twin_config(const SafetyMarginScenario& s, const SafetyMarginCase& k) {
  twin::TwinModelConfig c;
  c.model_path = s.model_path;
  c.keyframe = s.keyframe;
  c.coupling_stiffness_nm_per_rad = s.coupling_stiffness_nm_per_rad;
  c.coupling_damping_nms_per_rad = s.coupling_damping_nms_per_rad;
  // ee_site sits at (0, 0, 0.107) in link7
  for (const char* side : kSides) {
    c.margin_spheres.push_back(
        {std::string(side) + "_margin", std::string(side) + "_link7", {0, 0, 0.107}, s.sphere_radius_m});
  }
  c.margin_activation_m = k.activation_m;
  c.distance_pairs = {{"hands", "geom:left_margin", "geom:right_margin"}};
  return c;
}

double site_distance(const mjData* d, int a, int b) {
  const mjtNum* pa = d->site_xpos + 3 * a;
  const mjtNum* pb = d->site_xpos + 3 * b;
  return std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                   (pa[2] - pb[2]) * (pa[2] - pb[2]));
}

// The operator: `push_n` on each hand towards the other (J^T F on both arms), plus the damping of
// the operator's own arm on the device's joints.
class Operator {
 public:
  Operator(const mjModel* m, double push_n)
      : push_n_(push_n),
        left_(mj_name2id(m, mjOBJ_SITE, "left_ee_site")),
        right_(mj_name2id(m, mjOBJ_SITE, "right_ee_site")),
        jac_(3 * static_cast<size_t>(m->nv)) {}

  int left() const { return left_; }
  int right() const { return right_; }

  void torque(const mjModel* m, const mjData* d, teleop::JointVector& tau) {
    tau.fill(0.0);
    const mjtNum* pl = d->site_xpos + 3 * left_;
    const mjtNum* pr = d->site_xpos + 3 * right_;
    const double len = site_distance(d, left_, right_);
    for (const auto& [site, sign] : {std::pair{left_, 1.0}, std::pair{right_, -1.0}}) {
      mj_jacSite(m, d, jac_.data(), nullptr, site);
      for (int j = 0; j < m->nv; ++j) {
        for (int r = 0; r < 3; ++r) {
          tau[static_cast<size_t>(j)] += jac_[static_cast<size_t>(r * m->nv + j)] * sign * push_n_ * (pr[r] - pl[r]) / len;
        }
      }
    }
  }

 private:
  double push_n_;
  int left_;
  int right_;
  std::vector<mjtNum> jac_;
};

double min_pair_distance(const twin::TwinSimulation& sim) {
  double out = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < sim.config().distance_pairs.size(); ++i) out = std::min(out, sim.distance_m(i));
  return out;
}

}  // namespace

SafetyMarginResult run_safety_margin_case(const SafetyMarginScenario& s, const SafetyMarginCase& c,
                                          double feedback_gain) {
  twin::TwinSimulation physical(physical_config(s));
  twin::TwinSimulation twin(twin_config(s, c));
  const mjModel* m = physical.simulation().model();
  const mjData* d = physical.simulation().data();
  Operator op(m, s.push_n);
  const double dt = m->opt.timestep;
  LowPassFilter filter(s.lowpass_hz, 1.0 / dt);
  const long steps = std::lround(s.duration_s / dt);
  const long trace_every = std::max(1L, std::lround(s.trace_period_s / dt));
  const double rest_from_s = s.duration_s - s.rest_window_s;

  SafetyMarginResult r;
  r.config = c;
  double rest_twin = 0.0;
  double rest_physical = 0.0;
  long rest_n = 0;
  teleop::JointVector tau{};
  for (long k = 0; k < steps; ++k) {
    op.torque(m, d, tau);
    const teleop::JointVector& rendered = filter.apply(twin.constraint_torque_nm(), twin.joints());
    for (size_t i = 0; i < physical.joints(); ++i) {
      tau[i] += feedback_gain * rendered[i] - s.operator_damping_nms_per_rad * physical.dq_radps()[i];
    }
    physical.step_torque(tau);
    twin.step_coupled(physical.q_rad());
    const double t = static_cast<double>(k + 1) * dt;
    const double physical_margin = site_distance(d, op.left(), op.right()) - 2 * s.sphere_radius_m;
    const double twin_margin = twin.distance_m(0);
    const double arms = min_pair_distance(physical);
    r.min_physical_margin_m = std::min(r.min_physical_margin_m, physical_margin);
    r.min_twin_margin_m = std::min(r.min_twin_margin_m, twin_margin);
    r.min_arms_m = std::min(r.min_arms_m, arms);
    if (r.first_contact_s < 0 && twin_margin < c.activation_m) r.first_contact_s = t;
    if (t > rest_from_s) {
      rest_twin += twin_margin;
      rest_physical += physical_margin;
      ++rest_n;
    }
    if ((k + 1) % trace_every == 0) {
      r.trace.t_s.push_back(t);
      r.trace.twin_margin_m.push_back(twin_margin);
      r.trace.physical_margin_m.push_back(physical_margin);
      r.trace.arms_m.push_back(arms);
    }
  }
  if (rest_n > 0) {
    r.rest_twin_margin_m = rest_twin / static_cast<double>(rest_n);
    r.rest_physical_margin_m = rest_physical / static_cast<double>(rest_n);
  }
  r.warnings = physical.warnings() + twin.warnings();
  return r;
}

}  // namespace teleop::experiment
