#include "hand_plan.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::leader {

HandPlan::HandPlan(std::vector<HandKeyframe> keyframes) : keyframes_(std::move(keyframes)) {
  if (keyframes_.empty()) throw std::invalid_argument("a hand plan needs at least one keyframe");
  for (size_t i = 0; i < keyframes_.size(); ++i) {
    const HandKeyframe& k = keyframes_[i];
    const bool finite =
        std::isfinite(k.t_s) &&
        std::all_of(k.position_rad.begin(), k.position_rad.end(), [](double v) { return std::isfinite(v); }) &&
        std::all_of(k.current_limit_a.begin(), k.current_limit_a.end(),
                    [](double v) { return std::isfinite(v) && v >= 0; });
    if (!finite) throw std::invalid_argument("keyframe " + std::to_string(i) + " has a non-finite or negative value");
    if (i == 0 ? k.t_s < 0 : k.t_s <= keyframes_[i - 1].t_s) {
      throw std::invalid_argument("keyframe " + std::to_string(i) + ": times must start at 0 or later and increase");
    }
  }
}

void HandPlan::sample(double t_s, HandMotors& position_rad, HandMotors& current_limit_a) const {
  // the first keyframe at or after t (the last one once the plan is over)
  size_t next = 0;
  while (next < keyframes_.size() && keyframes_[next].t_s < t_s) ++next;
  if (next == 0 || next == keyframes_.size()) {
    const HandKeyframe& k = keyframes_[next == 0 ? 0 : next - 1];
    position_rad = k.position_rad;
    current_limit_a = k.current_limit_a;
    return;
  }
  const HandKeyframe& a = keyframes_[next - 1];
  const HandKeyframe& b = keyframes_[next];
  const double x = (t_s - a.t_s) / (b.t_s - a.t_s);
  const double s = x * x * (3.0 - 2.0 * x);  // smoothstep: at rest at both keyframes
  for (size_t m = 0; m < kHandMotors; ++m)
    position_rad[m] = a.position_rad[m] + s * (b.position_rad[m] - a.position_rad[m]);
  current_limit_a = b.current_limit_a;
}

HandPlan parse_hand_plan(const ConfigNode& section) {
  std::vector<HandKeyframe> keyframes;
  for (const ConfigNode& entry : section.get_node_list("plan")) {
    HandKeyframe k;
    k.t_s = entry.get_double("t_s", Range{0, 1e6});
    const auto read = [&](const std::string& key, Range range, HandMotors& out) {
      const std::vector<double> v = entry.get_double_list(key, range);
      if (v.size() != kHandMotors) throw entry.error(key, "needs 9 values (one per SVH motor)");
      std::copy(v.begin(), v.end(), out.begin());
    };
    read("position_rad", Range{-10, 10}, k.position_rad);
    if (entry.has("current_limit_a")) read("current_limit_a", Range{0, 100}, k.current_limit_a);
    if (!keyframes.empty() && k.t_s <= keyframes.back().t_s) throw entry.error("t_s", "times must increase");
    keyframes.push_back(k);
  }
  if (keyframes.empty()) throw section.error("plan", "needs at least one keyframe");
  return HandPlan(std::move(keyframes));
}

}  // namespace teleop::leader
