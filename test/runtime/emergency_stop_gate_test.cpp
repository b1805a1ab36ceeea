// The stop chain's end in every node: a stop addressed to the node reaches its logic before the
// work of the cycle that took it, stays latched until an enable, and the node reports it.
#include "emergency_stop_gate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <thread>

#include "test_participant.h"
#include "teleop/transport/publication.h"

namespace teleop::runtime {
namespace {

transport::ParticipantConfig config(const std::string& name) { return test::local_participant(name, 70); }

// a node's logic that says running and records, at each cycle's work, whether it was told to stop
class RecordingLogic final : public NodeLogic {
 public:
  void cycle(const CycleTick&) override {
    ++cycles;
    stopped_at_work = stopped;
  }
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>& faults) const override { faults.insert(faults.end(), own_faults.begin(), own_faults.end()); }
  void emergency_stop(bool engaged) override {
    stopped = engaged;
    ++told;
  }
  bool enable_requested() override {
    ++enable_requests;
    const bool ended = holding;
    holding = false;
    return ended;
  }
  void fill_report(NodeReport&) const override {}
  void trace_columns(std::vector<std::string>& columns) const override { columns.emplace_back("x"); }
  void trace_row(double* row) const override { row[0] = 7.0; }

  int cycles = 0;
  int told = 0;
  int enable_requests = 0;
  bool holding = false;  // a hold that waits for an enable
  bool stopped = false;
  bool stopped_at_work = false;
  std::vector<uint32_t> own_faults;
};

struct Bus {
  transport::Participant node_side{config("follower")};
  transport::Participant operator_side{config("operator")};
  transport::Publication<msg::EmergencyStop> requests{operator_side, transport::topics::kEmergencyStop, "operator"};
  RecordingLogic* logic = nullptr;
  std::unique_ptr<EmergencyStopGate> gate;
  CycleTick tick{};

  Bus() {
    auto owned = std::make_unique<RecordingLogic>();
    logic = owned.get();
    gate = std::make_unique<EmergencyStopGate>(std::move(owned), node_side, "follower");
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (requests.matched() == 0 && std::chrono::steady_clock::now() < end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  void send(bool engaged, const char* target) {
    requests.sample().engaged(engaged);
    requests.sample().target(target);
    requests.sample().origin("test");
    requests.publish();
    EXPECT_TRUE(requests.wait_for_acknowledgments(5'000'000'000));
  }
  // cycles until the logic was told as often as `told` (or 5 s passed)
  bool cycle_until_told(int told) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (logic->told < told) {
      if (std::chrono::steady_clock::now() > end) return false;
      ++tick.index;
      gate->cycle(tick);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
  }
  std::vector<uint32_t> faults() const {
    std::vector<uint32_t> f;
    gate->active_faults(f);
    return f;
  }
};

TEST(EmergencyStopGate, AStopReachesTheLogicBeforeTheWorkOfTheCycleThatTookIt) {
  Bus bus;
  ASSERT_GT(bus.requests.matched(), 0);
  bus.send(true, "");
  ASSERT_TRUE(bus.cycle_until_told(1));
  EXPECT_TRUE(bus.logic->stopped_at_work);
  EXPECT_TRUE(bus.gate->engaged());
  EXPECT_EQ(bus.gate->state(), msg::STATE_FAULT);
  EXPECT_EQ(bus.faults(), std::vector<uint32_t>{msg::FAULT_EMERGENCY_STOP});
}

TEST(EmergencyStopGate, OnlyAnEnableEndsIt) {
  Bus bus;
  bus.send(true, "");
  ASSERT_TRUE(bus.cycle_until_told(1));
  // a repeated stop changes nothing; cycles of a logic that says running leave it stopped
  bus.send(true, "follower");
  for (int i = 0; i < 50; ++i) bus.gate->cycle(bus.tick);
  EXPECT_EQ(bus.logic->told, 1);
  EXPECT_EQ(bus.gate->state(), msg::STATE_FAULT);
  bus.send(false, "");
  ASSERT_TRUE(bus.cycle_until_told(2));
  EXPECT_FALSE(bus.logic->stopped_at_work);
  EXPECT_EQ(bus.gate->state(), msg::STATE_RUNNING);
  EXPECT_TRUE(bus.faults().empty());
  NodeReport report;
  bus.gate->fill_report(report);
  const auto counter = [&](const std::string& name) {
    const auto it = std::find_if(report.counters.begin(), report.counters.end(), [&](const auto& c) { return c.first == name; });
    return it == report.counters.end() ? -1.0 : it->second;
  };
  EXPECT_EQ(counter("emergency_stops"), 1.0);
  EXPECT_EQ(counter("emergency_stop_enables"), 1.0);
  EXPECT_EQ(counter("emergency_stop_engaged"), 0.0);
  EXPECT_GE(counter("emergency_stop_reaction_max_ms"), 0.0);
}

// no emergency stop engaged: an enable goes to the logic, which may end a hold waiting for one
TEST(EmergencyStopGate, AnEnableWithoutAStopIsTheLogicsToEndAHoldWith) {
  Bus bus;
  bus.logic->holding = true;
  bus.send(false, "follower");
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (bus.logic->enable_requests == 0 && std::chrono::steady_clock::now() < end) {
    bus.gate->cycle(bus.tick);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(bus.logic->enable_requests, 1);
  EXPECT_FALSE(bus.logic->holding);
  EXPECT_EQ(bus.logic->told, 0) << "no emergency stop to end";
  bus.send(false, "");  // another: nothing left to end
  for (int i = 0; i < 50 && bus.logic->enable_requests < 2; ++i) {
    bus.gate->cycle(bus.tick);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  NodeReport report;
  bus.gate->fill_report(report);
  const auto it = std::find_if(report.counters.begin(), report.counters.end(), [](const auto& c) { return c.first == "hold_enables"; });
  ASSERT_NE(it, report.counters.end());
  EXPECT_EQ(it->second, 1.0);
  EXPECT_EQ(bus.gate->state(), msg::STATE_RUNNING);
}

TEST(EmergencyStopGate, AStopForAnotherNodeIsNotOurs) {
  Bus bus;
  bus.send(true, "leader");
  bus.send(true, "follower");
  ASSERT_TRUE(bus.cycle_until_told(1));
  bus.send(false, "leader");
  for (int i = 0; i < 50; ++i) bus.gate->cycle(bus.tick);
  EXPECT_TRUE(bus.gate->engaged());
  EXPECT_EQ(bus.logic->told, 1);
}

TEST(EmergencyStopGate, TheLogicsOwnHoldCauseIsNotReportedTwice) {
  Bus bus;
  bus.logic->own_faults = {msg::FAULT_EMERGENCY_STOP};
  bus.send(true, "");
  ASSERT_TRUE(bus.cycle_until_told(1));
  EXPECT_EQ(bus.faults(), std::vector<uint32_t>{msg::FAULT_EMERGENCY_STOP});
}

TEST(EmergencyStopGate, TheTraceGetsTheStopAfterTheLogicsColumns) {
  Bus bus;
  std::vector<std::string> columns;
  bus.gate->trace_columns(columns);
  EXPECT_EQ(columns, (std::vector<std::string>{"x", "emergency_stop"}));
  double row[2] = {0, -1};
  bus.gate->trace_row(row);
  EXPECT_EQ(row[0], 7.0);
  EXPECT_EQ(row[1], 0.0);
  bus.send(true, "");
  ASSERT_TRUE(bus.cycle_until_told(1));
  bus.gate->trace_row(row);
  EXPECT_EQ(row[1], 1.0);
}

}  // namespace
}  // namespace teleop::runtime
