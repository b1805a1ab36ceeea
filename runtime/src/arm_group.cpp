#include "teleop/runtime/arm_group.h"

#include <stdexcept>

namespace teleop::runtime {
namespace {

// higher is worse: what the group reports when its arms disagree
int severity(msg::NodeState s) {
  switch (s) {
    case msg::STATE_FAULT:
      return 4;
    case msg::STATE_SAFE_HOLD:
      return 3;
    case msg::STATE_STARTING:
      return 2;
    case msg::STATE_STOPPING:
      return 1;
    default:
      return 0;
  }
}

}  // namespace

ArmGroup::ArmGroup(std::vector<Arm> arms, std::function<void()> after_arms)
    : arms_(std::move(arms)), after_arms_(std::move(after_arms)) {
  if (arms_.empty()) throw std::invalid_argument("an arm group needs at least one arm");
  for (const Arm& a : arms_) {
    std::vector<std::string> columns;
    a.logic->trace_columns(columns);
    trace_widths_.push_back(columns.size());
  }
}

void ArmGroup::cycle(const CycleTick& tick) {
  for (Arm& a : arms_) a.logic->cycle(tick);
  if (after_arms_) after_arms_();
}

bool ArmGroup::enable_requested() {
  bool ended = false;
  for (Arm& a : arms_) ended = a.logic->enable_requested() || ended;  // every arm, not the first alone
  return ended;
}

void ArmGroup::emergency_stop(bool engaged) {
  for (Arm& a : arms_) a.logic->emergency_stop(engaged);
}

msg::NodeState ArmGroup::state() const {
  msg::NodeState worst = arms_.front().logic->state();
  for (const Arm& a : arms_) {
    if (severity(a.logic->state()) > severity(worst)) worst = a.logic->state();
  }
  return worst;
}

void ArmGroup::active_faults(std::vector<uint32_t>& faults) const {
  for (const Arm& a : arms_) a.logic->active_faults(faults);
}

void ArmGroup::fill_report(NodeReport& report) const {
  for (const Arm& a : arms_) {
    NodeReport part;
    a.logic->fill_report(part);
    report.published.insert(report.published.end(), part.published.begin(), part.published.end());
    report.received.insert(report.received.end(), part.received.begin(), part.received.end());
    for (const auto& [name, value] : part.counters) {
      report.counters.emplace_back(a.name.empty() ? name : a.name + "." + name, value);
    }
  }
}

void ArmGroup::trace_columns(std::vector<std::string>& columns) const {
  for (const Arm& a : arms_) {
    std::vector<std::string> own;
    a.logic->trace_columns(own);
    for (const std::string& c : own) columns.push_back(a.name.empty() ? c : a.name + "_" + c);
  }
}

void ArmGroup::trace_row(double* row) const {
  for (size_t i = 0; i < arms_.size(); ++i) {
    arms_[i].logic->trace_row(row);
    row += trace_widths_[i];
  }
}

}  // namespace teleop::runtime
