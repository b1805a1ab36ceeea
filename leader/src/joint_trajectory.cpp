#include "joint_trajectory.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "teleop/common/config.h"

namespace teleop::leader {
namespace {

ConfigError csv_error(const std::string& path, size_t line, const std::string& column, const std::string& problem) {
  return ConfigError(path + ":" + std::to_string(line) + ": " + column + ": " + problem);
}

// an error about the file as a whole (no line)
ConfigError file_error(const std::string& path, const std::string& what, const std::string& problem) {
  return ConfigError(path + ": " + what + ": " + problem);
}

std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  for (size_t comma = line.find(','); comma != std::string_view::npos; comma = line.find(',', start)) {
    fields.push_back(trimmed(line.substr(start, comma - start)));
    start = comma + 1;
  }
  fields.push_back(trimmed(line.substr(start)));
  return fields;
}

// the header row's column names, looked up by name
class Header {
 public:
  Header(const std::string& path, const std::string& line) : path_(path), text_(line), names_(split_fields(text_)) {}

  size_t size() const { return names_.size(); }
  bool has(const std::string& name) const { return std::find(names_.begin(), names_.end(), name) != names_.end(); }
  size_t index(const std::string& name) const {
    const auto it = std::find(names_.begin(), names_.end(), name);
    if (it == names_.end()) throw csv_error(path_, 1, name, "column missing from the header");
    return static_cast<size_t>(it - names_.begin());
  }
  std::vector<size_t> indices(const std::string& prefix, size_t count) const {
    std::vector<size_t> out;
    for (size_t j = 0; j < count; ++j) out.push_back(index(prefix + std::to_string(j)));
    return out;
  }

 private:
  std::string path_;
  std::string text_;  // owns what names_ views
  std::vector<std::string_view> names_;
};

// one CSV row being read: its fields and where it is, for errors
struct Row {
  const std::string& path;
  size_t line;
  std::vector<std::string_view> fields;

  double number(size_t column, const std::string& name) const {
    const std::string_view field = fields[column];
    double value = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (field.empty() || ec != std::errc() || end != field.data() + field.size())
      throw csv_error(path, line, name, "'" + std::string(field) + "' is not a number");
    if (!std::isfinite(value)) throw csv_error(path, line, name, "'" + std::string(field) + "' is not finite");
    return value;
  }
};

// central differences inside, one-sided at both ends
std::vector<double> finite_differences(const std::vector<double>& t_s, const std::vector<double>& q, size_t joints) {
  std::vector<double> dq(q.size());
  const size_t last = t_s.size() - 1;
  for (size_t i = 0; i <= last; ++i) {
    const size_t lo = i == 0 ? 0 : i - 1;
    const size_t hi = i == last ? last : i + 1;
    for (size_t j = 0; j < joints; ++j)
      dq[i * joints + j] = (q[hi * joints + j] - q[lo * joints + j]) / (t_s[hi] - t_s[lo]);
  }
  return dq;
}

}  // namespace

JointTrajectory JointTrajectory::load_csv(const std::string& path, size_t joints, const std::string& q_prefix) {
  if (joints < 1 || joints > kMaxJoints)
    throw file_error(path, "joints", std::to_string(joints) + " not in [1, " + std::to_string(kMaxJoints) + "]");
  std::ifstream in(path);
  std::string text;
  if (!in) throw file_error(path, "file", "cannot be opened");
  if (!std::getline(in, text)) throw csv_error(path, 1, "header", "missing (the file is empty)");
  const Header header(path, text);
  const size_t t_column = header.index("t_s");
  const std::vector<size_t> q_columns = header.indices(q_prefix, joints);
  const std::string dq_prefix = "d" + q_prefix;
  const bool has_velocities = header.has(dq_prefix + "0");
  const std::vector<size_t> dq_columns = has_velocities ? header.indices(dq_prefix, joints) : std::vector<size_t>{};
  const bool has_torques = header.has(std::string(kOperatorTorquePrefix) + "0");
  const std::vector<size_t> tau_columns = has_torques ? header.indices(kOperatorTorquePrefix, joints) : std::vector<size_t>{};

  std::vector<double> t_s, q, dq, tau;
  size_t line = 1;
  for (; std::getline(in, text); ++line) {
    if (trimmed(text).empty()) continue;
    const Row row{path, line + 1, split_fields(text)};
    if (row.fields.size() != header.size())
      throw csv_error(path, row.line, "row",
                      std::to_string(row.fields.size()) + " fields, the header has " + std::to_string(header.size()));
    const double t = row.number(t_column, "t_s");
    if (!t_s.empty() && !(t > t_s.back()))
      throw csv_error(path, row.line, "t_s",
                      std::to_string(t) + " is not after the previous row's " + std::to_string(t_s.back()));
    t_s.push_back(t);
    for (size_t j = 0; j < joints; ++j) q.push_back(row.number(q_columns[j], q_prefix + std::to_string(j)));
    for (size_t j = 0; j < dq_columns.size(); ++j)
      dq.push_back(row.number(dq_columns[j], dq_prefix + std::to_string(j)));
    for (size_t j = 0; j < tau_columns.size(); ++j)
      tau.push_back(row.number(tau_columns[j], kOperatorTorquePrefix + std::to_string(j)));
  }
  if (t_s.size() < 2)
    throw csv_error(path, line, "rows", std::to_string(t_s.size()) + " data row(s), a trajectory needs at least 2");

  // times relative to the first row
  const double t0 = t_s.front();
  for (double& t : t_s) t -= t0;
  if (!has_velocities) dq = finite_differences(t_s, q, joints);
  return JointTrajectory(joints, std::move(t_s), std::move(q), std::move(dq), std::move(tau));
}

JointTrajectory::JointTrajectory(size_t joints, std::vector<double> t_s, std::vector<double> q, std::vector<double> dq,
                                 std::vector<double> tau)
    : joints_(joints), t_s_(std::move(t_s)), q_(std::move(q)), dq_(std::move(dq)), tau_(std::move(tau)) {}

JointTrajectory::Segment JointTrajectory::locate(double t_s) const {
  const double end_s = duration_s();
  // looping: +Inf becomes NaN here and so holds the first row below
  if (loop_ && t_s >= end_s) t_s = std::fmod(t_s, end_s);
  if (!(t_s >= 0.0)) return {0, 0.0, true};
  if (t_s >= end_s) return {rows() - 1, 0.0, true};
  // the segment [t_i, t_i+1) holding t_s: binary search, no allocation
  const size_t i = static_cast<size_t>(std::upper_bound(t_s_.begin(), t_s_.end(), t_s) - t_s_.begin()) - 1;
  return {i, (t_s - t_s_[i]) / (t_s_[i + 1] - t_s_[i]), false};
}

void JointTrajectory::sample(double t_s, JointVector& q_rad, JointVector& dq_radps) const {
  const Segment segment = locate(t_s);
  if (segment.held) return hold(segment.row, q_rad, dq_radps);
  const size_t i = segment.row;
  const double w = segment.weight;
  const double* q0 = &q_[i * joints_];
  const double* dq0 = &dq_[i * joints_];
  for (size_t j = 0; j < joints_; ++j) {
    q_rad[j] = q0[j] + w * (q0[j + joints_] - q0[j]);
    dq_radps[j] = dq0[j] + w * (dq0[j + joints_] - dq0[j]);
  }
}

void JointTrajectory::sample_torque(double t_s, JointVector& tau_nm) const {
  if (tau_.empty()) {
    std::fill_n(tau_nm.begin(), joints_, 0.0);
    return;
  }
  const Segment segment = locate(t_s);
  const double* tau0 = &tau_[segment.row * joints_];
  for (size_t j = 0; j < joints_; ++j) tau_nm[j] = segment.held ? tau0[j] : tau0[j] + segment.weight * (tau0[j + joints_] - tau0[j]);
}

void JointTrajectory::hold(size_t row, JointVector& q_rad, JointVector& dq_radps) const {
  for (size_t j = 0; j < joints_; ++j) {
    q_rad[j] = q_[row * joints_ + j];
    dq_radps[j] = 0.0;
  }
}

}  // namespace teleop::leader
