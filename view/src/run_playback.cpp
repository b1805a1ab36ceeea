#include "teleop/view/run_playback.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace teleop::view {

namespace fs = std::filesystem;

namespace {

// a trace's times on the clock all traces of a run share: the wall clock when it was written
const std::vector<double>& clock_of(const experiment::Trace& trace) {
  return trace.has("wall_s") ? trace.column("wall_s") : trace.t_s;
}

std::string arm_prefix(const std::string& arm) { return arm.empty() ? "" : arm + "_"; }

}  // namespace

RunPlayback::Series RunPlayback::read_series(const std::string& path, Layer layer, const PosedScene& scene,
                                             bool required) const {
  Series s{layer, path, {}, {}, {}, {}, experiment::read_trace(path)};
  experiment::require_rows(s.trace);
  for (size_t a = 0; a < scene.arm_count(); ++a) {
    const std::string prefix = arm_prefix(scene.arm(a).name) + "q_";
    if (!s.trace.has(prefix + "0")) {
      if (!required) return Series{layer, path, {}, {}, {}, {}, {}};
      throw experiment::TraceError(path + ": no column '" + prefix + "0' for the joints of " +
                                   (scene.arm(a).name.empty() ? "the arm" : "arm " + scene.arm(a).name) + " of " +
                                   scene.spec().model_path + " (is it a trace of this scene's node?)");
    }
    s.arm_q.push_back(s.trace.numbered(prefix));
    if (s.arm_q.back().size() != scene.joint_count(a)) {
      throw experiment::TraceError(path + ": " + std::to_string(s.arm_q.back().size()) + " columns " + prefix +
                                   "<i>, the model's arm has " + std::to_string(scene.joint_count(a)) + " joints");
    }
    const std::string p = arm_prefix(scene.arm(a).name);
    if (layer == Layer::kFollower && s.trace.has(p + "f_ext_x") && s.trace.has(p + "x_x")) {
      s.forces.push_back(
          {{&s.trace.column(p + "x_x"), &s.trace.column(p + "x_y"), &s.trace.column(p + "x_z")},
           {&s.trace.column(p + "f_ext_x"), &s.trace.column(p + "f_ext_y"), &s.trace.column(p + "f_ext_z")}});
    }
  }
  if (layer == Layer::kFollower) {
    for (size_t b = 0; b < scene.free_bodies().size(); ++b) {
      const std::string& name = scene.free_bodies()[b].name;
      if (!s.trace.has(name + "_x") || !s.trace.has(name + "_y") || !s.trace.has(name + "_z")) continue;
      s.bodies.push_back(
          {b, {&s.trace.column(name + "_x"), &s.trace.column(name + "_y"), &s.trace.column(name + "_z")}});
    }
  }
  s.time_s = clock_of(s.trace);
  return s;
}

RunPlayback::RunPlayback(const std::string& run_dir, const PosedScene& scene, bool twin, bool leader) {
  series_.push_back(read_series((fs::path(run_dir) / "follower.csv").string(), Layer::kFollower, scene, true));
  for (const auto& [wanted, layer, file] :
       {std::tuple{twin, Layer::kTwin, "twin.csv"}, std::tuple{leader, Layer::kLeader, "leader.csv"}}) {
    const fs::path path = fs::path(run_dir) / file;
    if (!wanted || !fs::exists(path)) continue;
    Series s = read_series(path.string(), layer, scene, false);
    if (!s.arm_q.empty()) series_.push_back(std::move(s));
  }
  // the series were moved: their column pointers point into their own traces, which moved along
  // (a vector's buffer survives the move of the vector)
  origin_ = series_.front().time_s.front();
  for (Series& s : series_) {
    for (double& t : s.time_s) t -= origin_;
  }
}

double RunPlayback::duration_s() const { return series_.front().time_s.back(); }

std::string RunPlayback::sources() const {
  std::string out;
  for (const Series& s : series_) out += (out.empty() ? "" : ", ") + fs::path(s.file).filename().string();
  return out;
}

void RunPlayback::bracket(const Series& s, double t_s, size_t& i0, size_t& i1, double& w) {
  const auto it = std::lower_bound(s.time_s.begin(), s.time_s.end(), t_s);
  i1 = std::min(static_cast<size_t>(it - s.time_s.begin()), s.time_s.size() - 1);
  i0 = i1 > 0 ? i1 - 1 : 0;
  const double span = s.time_s[i1] - s.time_s[i0];
  w = span > 0 ? std::clamp((t_s - s.time_s[i0]) / span, 0.0, 1.0) : 1.0;
}

void RunPlayback::pose(PosedScene& scene, double t_s) const {
  for (const Series& s : series_) {
    if (t_s < s.time_s.front() || t_s > s.time_s.back()) {
      // a trace that had not started yet (or had ended): its layer is not shown then
      if (s.layer != Layer::kFollower) {
        scene.clear(s.layer);
        continue;
      }
    }
    size_t i0 = 0, i1 = 0;
    double w = 0;
    bracket(s, t_s, i0, i1, w);
    auto at = [&](const std::vector<double>& c) { return c[i0] + w * (c[i1] - c[i0]); };
    for (size_t a = 0; a < s.arm_q.size(); ++a) {
      std::vector<double> q;
      for (const auto* c : s.arm_q[a]) q.push_back(at(*c));
      scene.set_joints(s.layer, a, q.data(), q.size());
    }
    for (const auto& [body, xyz] : s.bodies) {
      const double p[3] = {at(*xyz[0]), at(*xyz[1]), at(*xyz[2])};
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      // the orientation is not traced: the keyframe's
      const mjData* d = scene.data(s.layer);
      const FreeBody& fb = scene.free_bodies()[body];
      double quat[4];
      std::copy_n(d->qpos + fb.qpos + 3, 4, quat);
      scene.set_body_pose(s.layer, body, p, quat);
    }
  }
}

std::vector<ForceArrow> RunPlayback::forces(double t_s) const {
  std::vector<ForceArrow> out;
  const Series& s = series_.front();
  size_t i0 = 0, i1 = 0;
  double w = 0;
  bracket(s, t_s, i0, i1, w);
  auto at = [&](const std::vector<double>& c) { return c[i0] + w * (c[i1] - c[i0]); };
  for (const auto& [x, f] : s.forces) {
    ForceArrow a;
    for (size_t k = 0; k < 3; ++k) {
      a.from[k] = at(*x[k]);
      a.force[k] = at(*f[k]);
    }
    out.push_back(a);
  }
  return out;
}

}  // namespace teleop::view
