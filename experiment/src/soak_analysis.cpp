#include "soak_analysis.h"

#include <teleop/msg/status.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "teleop/experiment/trace.h"

namespace teleop::experiment {
namespace {

struct ProcessTrace {
  const SoakProcess* process;
  Trace trace;
  double first_s() const { return trace.t_s.front(); }
  double last_s() const { return trace.t_s.back(); }
};

// a node still starting holds too: it has not been given anything to follow
bool is_state(double traced, msg::NodeState state) { return traced == static_cast<double>(state); }
bool safe(double state) {
  return is_state(state, msg::STATE_STARTING) || is_state(state, msg::STATE_SAFE_HOLD) || is_state(state, msg::STATE_FAULT);
}
bool running(double state) { return is_state(state, msg::STATE_RUNNING); }

// the trace of `node`'s process that was looping at `t_s`
const ProcessTrace* alive_at(const std::vector<ProcessTrace>& traces, const std::string& node, double t_s) {
  for (const ProcessTrace& p : traces) {
    if (p.process->node == node && p.first_s() <= t_s && t_s <= p.last_s()) return &p;
  }
  return nullptr;
}

const ProcessTrace* process_of(const std::vector<ProcessTrace>& traces, const std::string& node, int incarnation) {
  for (const ProcessTrace& p : traces) {
    if (p.process->node == node && p.process->incarnation == incarnation) return &p;
  }
  return nullptr;
}

// seconds from `from_s` to the first row at or after it whose state passes `pass`; NaN if none
template <typename Pass>
double until_state(const Trace& trace, double from_s, Pass pass) {
  const auto& state = trace.column("state");
  const auto begin = std::lower_bound(trace.t_s.begin(), trace.t_s.end(), from_s);
  for (auto it = begin; it != trace.t_s.end(); ++it) {
    if (pass(state[static_cast<size_t>(it - trace.t_s.begin())])) return *it - from_s;
  }
  return NAN;
}

// How the watchers of an event reacted: after how long the slowest got there (NaN: one never
// did while it was watched), whether that one was killed before the soak ended, and for how long
// it was watched.
struct Reaction {
  double after_s = 0.0;
  bool cut_short = false;
  double watched_s = 0.0;
};

template <typename Pass>
Reaction slowest(const std::vector<ProcessTrace>& traces, const std::vector<std::string>& watchers, double from_s,
                 double soak_end_s, Pass pass) {
  Reaction r;
  for (const std::string& w : watchers) {
    const ProcessTrace* p = alive_at(traces, w, from_s);
    const double t = p ? until_state(p->trace, from_s, pass) : NAN;
    if (std::isnan(t)) {
      r.after_s = NAN;
      r.cut_short = p != nullptr && p->last_s() < soak_end_s - 1.0;
      r.watched_s = p != nullptr ? p->last_s() - from_s : 0.0;
      return r;
    }
    r.after_s = std::max(r.after_s, t);
  }
  return r;
}

// every cycle of one process of the robot node
void check_robot(const Trace& t, SoakResult& result) {
  const auto& state = t.column("state");
  const auto& session = t.column("cmd_session");
  const auto& seq = t.column("cmd_seq");
  const auto& torque = t.column("torque_ratio");
  const auto& reflex = t.column("reflex");
  const auto& ratio = t.column("reflex_ratio");
  result.robot_cycles += t.t_s.size();
  for (size_t i = 0; i < t.t_s.size(); ++i) {
    if (i > 0 && running(state[i]) &&
        (session[i] < session[i - 1] || (session[i] == session[i - 1] && seq[i] < seq[i - 1]))) {
      ++result.stale_commands;
    }
    if (torque[i] > 1.0 + 1e-9) ++result.torque_violations;
    if (ratio[i] > 1.0 && reflex[i] == 0.0) ++result.reflex_violations;
    if (reflex[i] != 0.0 && (i == 0 || reflex[i - 1] == 0.0)) ++result.reflex_trips;
  }
}

double percentile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  // nearest rank
  const auto rank = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[rank == 0 ? 0 : rank - 1];
}

}  // namespace

void analyse_soak(const SoakConfig& config, const std::vector<SoakProcess>& processes, SoakResult& result) {
  std::vector<ProcessTrace> traces;
  for (const SoakProcess& p : processes) {
    try {
      Trace t = read_trace(p.trace);
      require_rows(t);
      traces.push_back({&p, std::move(t)});
    } catch (const TraceError& e) {
      std::fprintf(stderr, "[soak    ] %s\n", e.what());
      ++result.failures;
    }
  }
  double soak_end_s = 0.0;
  for (const ProcessTrace& p : traces) soak_end_s = std::max(soak_end_s, p.last_s());
  for (SoakEvent& e : result.events) {
    if (const ProcessTrace* next = process_of(traces, e.node, e.incarnation + 1)) e.first_cycle_s = next->first_s();
    const std::vector<std::string>& watchers = config.watch.at(e.node);
    e.to_safe_s = slowest(traces, watchers, e.killed_s, soak_end_s, safe).after_s;
    if (std::isnan(e.first_cycle_s)) continue;
    const Reaction resume = slowest(traces, watchers, e.first_cycle_s, soak_end_s, running);
    e.to_resume_s = resume.after_s;
    e.interrupted = std::isnan(resume.after_s) && resume.cut_short;
    e.pending = std::isnan(resume.after_s) && !resume.cut_short && resume.watched_s < config.resume_timeout_s;
  }
  for (const ProcessTrace& p : traces) {
    if (p.process->node != config.robot) continue;
    try {
      check_robot(p.trace, result);
    } catch (const TraceError& e) {
      std::fprintf(stderr, "[soak    ] %s\n", e.what());
      ++result.failures;
    }
  }
}

std::string soak_csv(const SoakResult& result) {
  std::ostringstream out;
  out << "node,incarnation,killed_s,restarted_s,first_cycle_s,to_safe_ms,to_resume_ms,interrupted,pending\n";
  char line[256];
  for (const SoakEvent& e : result.events) {
    std::snprintf(line, sizeof line, "%s,%d,%.6f,%.6f,%.6f,%.3f,%.3f,%d,%d\n", e.node.c_str(), e.incarnation, e.killed_s,
                  e.restarted_s, e.first_cycle_s, e.to_safe_s * 1e3, e.to_resume_s * 1e3, e.interrupted ? 1 : 0,
                  e.pending ? 1 : 0);
    out << line;
  }
  return out.str();
}

std::string format_soak(const SoakResult& result, const std::string& name) {
  std::map<std::string, std::vector<const SoakEvent*>> by_node;
  for (const SoakEvent& e : result.events) by_node[e.node].push_back(&e);
  std::ostringstream out;
  char line[256];
  out << "soak " << name << "\n";
  std::snprintf(line, sizeof line, "%-10s %6s %14s %14s %16s %16s %11s %7s %11s\n", "killed", "events", "to_safe_p50_ms",
                "to_safe_max_ms", "to_resume_p50_ms", "to_resume_max_ms", "interrupted", "pending", "unrecovered");
  out << line;
  for (const auto& [node, events] : by_node) {
    std::vector<double> to_safe, to_resume;
    int interrupted = 0;
    int pending = 0;
    int unrecovered = 0;
    for (const SoakEvent* e : events) {
      to_safe.push_back(e->to_safe_s * 1e3);
      to_resume.push_back(e->to_resume_s * 1e3);
      if (e->interrupted) ++interrupted;
      if (e->pending) ++pending;
      if (e->unrecovered()) ++unrecovered;
    }
    std::snprintf(line, sizeof line, "%-10s %6zu %14.1f %14.1f %16.1f %16.1f %11d %7d %11d\n", node.c_str(),
                  events.size(), percentile(to_safe, 0.5), percentile(to_safe, 1.0), percentile(to_resume, 0.5),
                  percentile(to_resume, 1.0), interrupted, pending, unrecovered);
    out << line;
  }
  std::snprintf(line, sizeof line,
                "robot cycles %llu: stale commands applied %llu, torque-limit violations %llu, reflex-threshold "
                "violations %llu, reflex trips %llu\n",
                static_cast<unsigned long long>(result.robot_cycles), static_cast<unsigned long long>(result.stale_commands),
                static_cast<unsigned long long>(result.torque_violations),
                static_cast<unsigned long long>(result.reflex_violations), static_cast<unsigned long long>(result.reflex_trips));
  out << line;
  return out.str();
}

}  // namespace teleop::experiment
