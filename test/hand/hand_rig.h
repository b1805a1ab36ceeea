#pragma once
// Test rig: the hand adapter and nine emulated drives on one VirtualCanBus, run in simulated
// time (the adapter's cycle, then the drives stepped through the cycle in 1 ms steps). The
// drives turn their own links, or the channels of a shared plant (the MuJoCo hand).

#include <cstdint>
#include <memory>
#include <vector>

#include "teleop/can/virtual_can_bus.h"
#include "teleop/drive/drive_group.h"
#include "teleop/hand/hand_adapter.h"

namespace teleop::hand::test {

using namespace can;  // the CANopen core the hand is built on

class HandRig {
 public:
  /// Drives for every node of the config except those in `missing`; node k of the config's
  /// list turns channel k of `plant` (null: each its own link).
  explicit HandRig(const HandAdapterConfig& config = {}, std::vector<NodeId> missing = {},
                   drive::SharedDrivePlant* plant = nullptr)
      : adapter_ep_(bus_.open("adapter")), adapter_(*adapter_ep_, config) {
    std::vector<drive::DriveGroupNode> nodes;
    for (size_t k = 0; k < config.node_ids.size(); ++k) {
      const NodeId node = config.node_ids[k];
      bool skip = false;
      for (NodeId m : missing) skip = skip || m == node;
      if (skip) continue;
      endpoints_.push_back(bus_.open("node"));
      drive::DriveGroupNode n;
      n.bus = endpoints_.back().get();
      n.config.node_id = node;
      n.config.serial = node;
      n.channel = k;
      nodes.push_back(n);
    }
    hand_ = std::make_unique<drive::DriveGroup>(nodes, plant);
  }

  HandAdapter& adapter() { return adapter_; }
  VirtualCanEndpoint& adapter_endpoint() { return *adapter_ep_; }
  VirtualCanBus& bus() { return bus_; }
  drive::EmulatedDrive& drive(size_t i) { return hand_->drive(i); }
  size_t drives() const { return hand_->drives(); }
  drive::DriveGroup& hand() { return *hand_; }
  int64_t now_ns() const { return now_ns_; }
  double period_s() const { return 1.0 / adapter_.config().cycle_rate_hz; }

  /// The bus endpoint of drive i (fault injection: frames taken from it never reach the drive).
  VirtualCanEndpoint& drive_endpoint(size_t i) { return *endpoints_[i]; }

  /// One adapter cycle, then `between` (e.g. taking frames off the bus), then the drives run
  /// until the next one.
  template <typename F>
  void cycle(F between) {
    adapter_.cycle(now_ns_);
    between();
    const auto period_ns = static_cast<int64_t>(period_s() * 1e9);
    for (int64_t t = 0; t < period_ns; t += 1'000'000) {
      hand_->step(static_cast<double>(std::min<int64_t>(1'000'000, period_ns - t)) * 1e-9);
    }
    now_ns_ += period_ns;
  }
  void cycle() {
    cycle([] {});
  }
  /// Cycles for `seconds` of simulated time.
  void run(double seconds) {
    const auto n = static_cast<int>(seconds / period_s());
    for (int i = 0; i < n; ++i) cycle();
  }
  /// Cycles until the adapter is in `phase` (true) or `seconds` passed (false).
  bool run_until(HandPhase phase, double seconds = 5.0) {
    const auto n = static_cast<int>(seconds / period_s());
    for (int i = 0; i < n && adapter_.phase() != phase; ++i) cycle();
    return adapter_.phase() == phase;
  }

 private:
  VirtualCanBus bus_;
  std::unique_ptr<VirtualCanEndpoint> adapter_ep_;
  HandAdapter adapter_;
  std::vector<std::unique_ptr<VirtualCanEndpoint>> endpoints_;
  std::unique_ptr<drive::DriveGroup> hand_;
  int64_t now_ns_ = 0;
};

}  // namespace teleop::hand::test
