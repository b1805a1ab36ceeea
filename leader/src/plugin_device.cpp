#include "plugin_device.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace teleop::leader {

PluginLibrary::PluginLibrary(const std::string& path) : path_(path) {
  handle_ = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) throw std::runtime_error("cannot load " + path + ": " + ::dlerror());
  const auto entry = reinterpret_cast<teleop_device_v1_entry_fn>(::dlsym(handle_, TELEOP_DEVICE_V1_ENTRY));
  if (entry == nullptr) {
    ::dlclose(handle_);
    throw std::runtime_error(path + " exports no " TELEOP_DEVICE_V1_ENTRY
                             ": not a teleop device plugin");
  }
  api_ = entry();
  const auto refuse = [&](const std::string& problem) {
    ::dlclose(handle_);
    throw std::runtime_error(path + " " + problem);
  };
  if (api_ == nullptr) refuse("returned no interface");
  if (api_->abi != TELEOP_DEVICE_V1) refuse("speaks teleop_device ABI " + std::to_string(api_->abi) + ", not 1");
  if (api_->kind != TELEOP_DEVICE_JOINTS && api_->kind != TELEOP_DEVICE_CARTESIAN) refuse("declares an unknown kind");
  if (!api_->open || !api_->read || !api_->write || !api_->last_error || !api_->close) refuse("lacks a function");
}

PluginLibrary::~PluginLibrary() { ::dlclose(handle_); }

PluginDevice::PluginDevice(std::shared_ptr<const PluginLibrary> library, const PluginSettings& settings,
                           double period_s, size_t leader_joints)
    : library_(std::move(library)), api_(library_->api()) {
  std::vector<const char*> keys;
  std::vector<const char*> values;
  for (const auto& [key, value] : settings) {
    keys.push_back(key.c_str());
    values.push_back(value.c_str());
  }
  device_ = api_.open(keys.data(), values.data(), static_cast<uint32_t>(keys.size()), period_s, &info_);
  const std::string what = "leader.plugin: " + library_->path();
  if (device_ == nullptr) throw std::runtime_error(what + ": " + api_.last_error(nullptr));
  info_.name[sizeof info_.name - 1] = '\0';
  const auto refuse = [&](const std::string& problem) {
    api_.close(device_);
    throw std::runtime_error(what + " (" + info_.name + ") " + problem);
  };
  if (info_.feedback_dof > TELEOP_DEVICE_MAX_DOF || info_.joints > TELEOP_DEVICE_MAX_DOF || info_.joints > kMaxJoints) {
    refuse("declares more joints or efforts than it may");
  }
  if (library_->cartesian() && info_.feedback_dof != 0 && info_.feedback_dof != 3 && info_.feedback_dof != 6) {
    refuse("is Cartesian: it renders 0, 3 or 6 efforts, not " + std::to_string(info_.feedback_dof));
  }
  if (!library_->cartesian() && info_.joints != leader_joints) {
    refuse("has " + std::to_string(info_.joints) + " joints, leader.joints says " + std::to_string(leader_joints));
  }
  if (!library_->cartesian() && info_.feedback_dof != 0 && info_.feedback_dof != info_.joints) {
    refuse("renders " + std::to_string(info_.feedback_dof) + " torques on " + std::to_string(info_.joints) + " joints");
  }
  for (uint32_t k = 0; k < info_.feedback_dof; ++k) {
    if (!(info_.max_feedback[k] >= 0.0) || !std::isfinite(info_.max_feedback[k])) refuse("declares a bad effort limit");
  }
}

PluginDevice::~PluginDevice() {
  if (failed_reads_ + invalid_reads_ + failed_writes_ > 0) {
    std::fprintf(stderr, "leader.plugin: %s: %llu failed reads, %llu not finite, %llu failed writes; the last: %s\n",
                 info_.name, static_cast<unsigned long long>(failed_reads_),
                 static_cast<unsigned long long>(invalid_reads_), static_cast<unsigned long long>(failed_writes_),
                 last_error_);
  }
  api_.close(device_);
}

// the plugin's message, kept without allocating for the log at close
void PluginDevice::keep_error() {
  std::strncpy(last_error_, api_.last_error(device_), sizeof last_error_ - 1);
  last_error_[sizeof last_error_ - 1] = '\0';
}

bool PluginDevice::finite(const teleop_device_state& s) const {
  const auto all = [](const double* v, size_t n) { return std::all_of(v, v + n, [](double x) { return std::isfinite(x); }); };
  if (library_->cartesian()) return all(s.position_m, 3) && all(s.orientation_wxyz, 4) && all(s.twist, 6);
  return all(s.q_rad, info_.joints) && all(s.dq_radps, info_.joints);
}

bool PluginDevice::read(DeviceState& state) {
  if (api_.read(device_, &state_) != 0) {
    ++failed_reads_;
    keep_error();
    return false;
  }
  if (!finite(state_)) {
    ++invalid_reads_;
    std::snprintf(last_error_, sizeof last_error_, "a measurement that is not finite");
    return false;
  }
  if (library_->cartesian()) {
    std::copy_n(state_.position_m, 3, state.position_m.begin());
    std::copy_n(state_.orientation_wxyz, 4, state.orientation_wxyz.begin());
    std::copy_n(state_.twist, 6, state.twist.begin());
  } else {
    std::copy_n(state_.q_rad, info_.joints, state.q_rad.begin());
    std::copy_n(state_.dq_radps, info_.joints, state.dq_radps.begin());
  }
  state.buttons |= state_.buttons;
  return true;
}

bool PluginDevice::write(const JointVector& feedback_nm) {
  if (info_.feedback_dof == 0) return true;
  for (uint32_t k = 0; k < info_.feedback_dof; ++k) {
    const double limit = info_.max_feedback[k];
    // not finite: nothing (the renderer never gives one; a plugin must never see one)
    const double e = std::isfinite(feedback_nm[k]) ? feedback_nm[k] : 0.0;
    effort_[k] = std::clamp(e, -limit, limit);
    if (effort_[k] != e) ++limited_efforts_;
  }
  if (api_.write(device_, effort_.data(), info_.feedback_dof) != 0) {
    ++failed_writes_;
    keep_error();
    return false;
  }
  return true;
}

void PluginDevice::report_counters(std::vector<std::pair<std::string, double>>& counters) const {
  counters.emplace_back("plugin_failed_reads", static_cast<double>(failed_reads_));
  counters.emplace_back("plugin_invalid_reads", static_cast<double>(invalid_reads_));
  counters.emplace_back("plugin_failed_writes", static_cast<double>(failed_writes_));
  counters.emplace_back("plugin_limited_efforts", static_cast<double>(limited_efforts_));
}

}  // namespace teleop::leader
