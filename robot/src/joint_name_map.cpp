#include "joint_name_map.h"

#include <algorithm>

namespace teleop::robot {
namespace {

constexpr size_t kAbsent = static_cast<size_t>(-1);

std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

JointNameMap::JointNameMap(std::vector<std::string> joints, std::vector<std::string> ignored)
    : joints_(std::move(joints)), ignored_(std::move(ignored)), index_(joints_.size(), kAbsent) {}

bool JointNameMap::ignored(const std::string& name) const {
  return std::find(ignored_.begin(), ignored_.end(), name) != ignored_.end();
}

bool JointNameMap::map(const std::vector<std::string>& names) {
  std::fill(index_.begin(), index_.end(), kAbsent);
  for (size_t k = 0; k < names.size(); ++k) {
    const auto joint = std::find(joints_.begin(), joints_.end(), names[k]);
    if (joint == joints_.end()) {
      if (!ignored(names[k])) return false;
      continue;
    }
    size_t& slot = index_[static_cast<size_t>(joint - joints_.begin())];
    if (slot != kAbsent) return false;  // named twice
    slot = k;
  }
  return std::none_of(index_.begin(), index_.end(), [](size_t i) { return i == kAbsent; });
}

std::string JointNameMap::mismatch(const std::vector<std::string>& names) const {
  std::vector<std::string> missing;
  std::vector<std::string> twice;
  std::vector<std::string> unexpected;
  for (const std::string& joint : joints_) {
    const auto count = std::count(names.begin(), names.end(), joint);
    if (count == 0) missing.push_back(joint);
    if (count > 1) twice.push_back(joint);
  }
  for (const std::string& name : names) {
    if (std::find(joints_.begin(), joints_.end(), name) == joints_.end() && !ignored(name)) unexpected.push_back(name);
  }
  std::string text;
  const auto add = [&text](const char* what, const std::vector<std::string>& which) {
    if (which.empty()) return;
    text += (text.empty() ? "" : "; ") + std::string(what) + listed(which);
  };
  add("missing: ", missing);
  add("named twice: ", twice);
  add("not configured (ros2.joints or ros2.ignored_joints): ", unexpected);
  return text;
}

}  // namespace teleop::robot
