// teleop_synthetic_trace_node: a test-only node on run_node whose trace has the columns the
// experiment analysis reads, filled with signals of known relation, so that `--trace` and
// `teleop experiment` can be tested end to end with real processes (the real leader and follower
// get their trace columns with the teleoperation architectures).
//
// Both roles evaluate the same smooth function of CLOCK_MONOTONIC time, so across two processes
// the follower's position is the leader's command plus a fixed offset:
//   leader:   x_cmd = (0.5, 0.01 sin(t), 0.2),  f_felt = (0, 0, 10)
//   follower: x = x_cmd + (0.003, 0, -0.004),   f_ext = (0, 6, 18), joints still
// so tracking error 0.005 m, force error 10 N, felt 10 N, exerted sqrt(360) N, MAD 0. A follower
// takes its first command `synthetic.follows_after_s` after its start (a late discovery when
// large) and, given `synthetic.reflex_after_s`, latches its speed reflex then.
#include <cmath>
#include <limits>

#include "teleop/runtime/node_runner.h"

namespace {

using teleop::ConfigNode;
using teleop::CycleTick;
using teleop::runtime::NodeContext;
using teleop::runtime::NodeReport;

struct SyntheticConfig {
  bool follower = false;
  double follows_after_s = 0.0;
  double reflex_after_s = std::numeric_limits<double>::infinity();
};

class SyntheticTraceNode : public teleop::runtime::NodeLogic {
 public:
  static SyntheticConfig parse_config(const ConfigNode& root) {
    const ConfigNode s = root.child("synthetic");
    SyntheticConfig c;
    c.follower = s.get_choice("role", {"leader", "follower"}) == "follower";
    c.follows_after_s = s.get_double("follows_after_s", teleop::Range{0, 1e3}, c.follows_after_s);
    if (s.has("reflex_after_s")) c.reflex_after_s = s.get_double("reflex_after_s", teleop::Range{0, 1e3});
    return c;
  }
  SyntheticTraceNode(SyntheticConfig config, NodeContext&) : config_(config) {}

  void cycle(const CycleTick& tick) override {
    t_s_ = static_cast<double>(tick.now_ns) * 1e-9;
    if (start_s_ < 0) start_s_ = t_s_;
  }
  teleop::msg::NodeState state() const override { return teleop::msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(NodeReport&) const override {}

  void trace_columns(std::vector<std::string>& columns) const override {
    if (!config_.follower) {
      columns = {"x_cmd_x", "x_cmd_y", "x_cmd_z", "f_felt_x", "f_felt_y", "f_felt_z", "tdpa_w_j", "state"};
      return;
    }
    columns = {"x_x", "x_y", "x_z", "f_ext_x", "f_ext_y", "f_ext_z", "tdpa_w_j", "torque_ratio", "state", "cmd_session",
               "reflex"};
    for (int j = 0; j < 7; ++j) columns.push_back("q_" + std::to_string(j));
  }

  void trace_row(double* row) const override {
    const double y = 0.01 * std::sin(t_s_);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double state = static_cast<double>(teleop::msg::STATE_RUNNING);
    if (!config_.follower) {
      const double values[] = {0.5, y, 0.2, 0.0, 0.0, 10.0, nan, state};
      std::copy(std::begin(values), std::end(values), row);
      return;
    }
    const double since_s = t_s_ - start_s_;
    const double session = since_s >= config_.follows_after_s ? 1.0 : 0.0;
    const double reflex = since_s >= config_.reflex_after_s ? 4.0 : 0.0;  // the joint speed's (safety_reflex.h)
    const double values[] = {0.503, y,     0.196,  0.0, 6.0, 18.0, nan, 0.3, state, session,
                             reflex, 0.0, -0.2, 0.0, -2.1, 0.0, 3.4, 0.8};
    std::copy(std::begin(values), std::end(values), row);
  }

 private:
  SyntheticConfig config_;
  double t_s_ = 0.0;
  double start_s_ = -1.0;
};

}  // namespace

int main(int argc, char** argv) {
  return teleop::runtime::run_node(
      argc, argv,
      {teleop::msg::ROLE_TOOL, "synthetic", "test node: writes a trace of synthetic leader or follower signals",
       teleop::runtime::parser_for<SyntheticTraceNode>()});
}
