#pragma once
// The stop chain's end in every node (docs/stop_chain.md): the runner wraps the node's logic in
// this gate, which takes the emergency stops and enables addressed to the node (teleop/emergency_stop)
// at the start of each cycle, tells the logic before that cycle's work, and keeps the stop latched:
// only an enable ends it; a new command session, a returning link or a restarted peer do not.
// While it is engaged the node reports STATE_FAULT with FAULT_EMERGENCY_STOP, whatever its logic
// says, so that no node reads as running while stopped. A peer of another protocol or message
// version, or one playing another teleoperation architecture, on the domain stops the node the same
// way (FAULT_VERSION_MISMATCH, FAULT_ARCHITECTURE_MISMATCH while it talks, peer_agreement.h); no
// enable is taken until it is gone.

#include <teleop/msg/status.h>

#include <array>
#include <memory>
#include <string>

#include "peer_agreement.h"
#include "teleop/common/node_event.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/reader.h"

namespace teleop::runtime {

class EmergencyStopGate final : public NodeLogic {
 public:
  /// `architecture`: the teleoperation architecture the node plays (empty: none).
  EmergencyStopGate(std::unique_ptr<NodeLogic> logic, transport::Participant& participant, std::string node_name,
                    std::string architecture = {});

  /// Takes what arrived, tells the logic of a change, then runs its cycle. Real-time safe.
  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return engaged_ ? msg::STATE_FAULT : logic_->state(); }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void emergency_stop(bool engaged) override;
  void fill_status(msg::NodeStatus& status) const override { logic_->fill_status(status); }
  void fill_report(NodeReport& report) const override;
  int64_t pacing_phase_ns() const override { return logic_->pacing_phase_ns(); }
  /// The logic's columns and `emergency_stop` (1 while engaged) after them.
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  bool engaged() const { return engaged_; }
  const NodeLogic& logic() const { return *logic_; }

 private:
  bool addressed_to_us(const msg::EmergencyStop& request) const;
  /// `hold`: an enable that ended the logic's hold (no emergency stop was engaged).
  void log_change(const msg::EmergencyStop& request, int64_t now_ns, bool hold);
  /// Stops the node when a peer that disagrees appears, logs it when it goes.
  void watch_peers(int64_t now_ns);
  void watch_peer(Disagreement what, int64_t now_ns);
  bool any_mismatch() const { return mismatched_[0] || mismatched_[1]; }

  std::unique_ptr<NodeLogic> logic_;
  std::string name_;
  transport::Reader<msg::EmergencyStop> requests_;
  msg::EmergencyStop request_;
  NodeEventQueue* events_;
  PeerAgreement peers_;
  bool engaged_ = false;
  std::array<bool, kDisagreements> mismatched_{};  // by Disagreement
  std::array<uint64_t, kDisagreements> mismatch_stops_{};
  uint64_t enables_refused_ = 0;
  uint64_t stops_ = 0;
  uint64_t enables_ = 0;
  uint64_t hold_enables_ = 0;  // enables that ended a hold waiting for one
  // from a request's arrival at the reader to the start of the cycle that acted on it [ns]
  int64_t reaction_max_ns_ = 0;
  mutable size_t logic_columns_ = 0;  // set once by trace_columns()
};

}  // namespace teleop::runtime
