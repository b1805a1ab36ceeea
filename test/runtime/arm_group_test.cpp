#include "teleop/runtime/arm_group.h"

#include <gtest/gtest.h>

#include <cmath>

namespace teleop::runtime {
namespace {

// an arm logic whose state, faults, report and trace a test sets
class FakeArm final : public NodeLogic {
 public:
  FakeArm(msg::NodeState state, uint32_t fault, double value, std::vector<int>* order, int id)
      : state_(state), fault_(fault), value_(value), order_(order), id_(id) {}
  void cycle(const CycleTick&) override { order_->push_back(id_); }
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override {
    if (fault_ != 0) faults.push_back(fault_);
  }
  void fill_report(NodeReport& report) const override { report.counters.emplace_back("trips", value_); }
  void trace_columns(std::vector<std::string>& columns) const override {
    columns.emplace_back("x");
    columns.emplace_back("y");
  }
  void trace_row(double* row) const override {
    row[0] = value_;
    row[1] = -value_;
  }

 private:
  msg::NodeState state_;
  uint32_t fault_;
  double value_;
  std::vector<int>* order_;
  int id_;
};

ArmGroup group_of(msg::NodeState left, msg::NodeState right, std::vector<int>* order, std::function<void()> after = {}) {
  std::vector<ArmGroup::Arm> arms;
  arms.push_back({"left", std::make_unique<FakeArm>(left, 0, 1.0, order, 1)});
  arms.push_back({"right", std::make_unique<FakeArm>(right, msg::FAULT_STALE_INPUT, 2.0, order, 2)});
  return ArmGroup(std::move(arms), std::move(after));
}

TEST(ArmGroup, CyclesEveryArmInOrderThenTheCommonStep) {
  std::vector<int> order;
  ArmGroup group = group_of(msg::STATE_RUNNING, msg::STATE_RUNNING, &order, [&] { order.push_back(0); });
  group.cycle(CycleTick{});
  group.cycle(CycleTick{});
  EXPECT_EQ(order, (std::vector<int>{1, 2, 0, 1, 2, 0}));
}

TEST(ArmGroup, ReportsTheWorstStateOfItsArms) {
  std::vector<int> order;
  EXPECT_EQ(group_of(msg::STATE_RUNNING, msg::STATE_RUNNING, &order).state(), msg::STATE_RUNNING);
  EXPECT_EQ(group_of(msg::STATE_RUNNING, msg::STATE_SAFE_HOLD, &order).state(), msg::STATE_SAFE_HOLD);
  EXPECT_EQ(group_of(msg::STATE_FAULT, msg::STATE_SAFE_HOLD, &order).state(), msg::STATE_FAULT);
  EXPECT_EQ(group_of(msg::STATE_STARTING, msg::STATE_RUNNING, &order).state(), msg::STATE_STARTING);
}

TEST(ArmGroup, NamesEachArmsCountersAndTraceColumnsAndCollectsTheirFaults) {
  std::vector<int> order;
  ArmGroup group = group_of(msg::STATE_RUNNING, msg::STATE_RUNNING, &order);
  std::vector<uint32_t> faults;
  group.active_faults(faults);
  EXPECT_EQ(faults, (std::vector<uint32_t>{msg::FAULT_STALE_INPUT}));
  NodeReport report;
  group.fill_report(report);
  ASSERT_EQ(report.counters.size(), 2u);
  EXPECT_EQ(report.counters[0], (std::pair<std::string, double>{"left.trips", 1.0}));
  EXPECT_EQ(report.counters[1], (std::pair<std::string, double>{"right.trips", 2.0}));
  std::vector<std::string> columns;
  group.trace_columns(columns);
  EXPECT_EQ(columns, (std::vector<std::string>{"left_x", "left_y", "right_x", "right_y"}));
  double row[4] = {NAN, NAN, NAN, NAN};
  group.trace_row(row);
  EXPECT_EQ(row[0], 1.0);
  EXPECT_EQ(row[1], -1.0);
  EXPECT_EQ(row[2], 2.0);
  EXPECT_EQ(row[3], -2.0);
}

}  // namespace
}  // namespace teleop::runtime
