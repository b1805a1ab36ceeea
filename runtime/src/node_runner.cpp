#include "teleop/runtime/node_runner.h"

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <sys/prctl.h>

#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "emergency_stop_gate.h"
#include "flow_watch.h"
#include "node_event_log.h"
#include "status_publisher.h"
#include "teleop/common/clock.h"
#include "teleop/common/data_paths.h"
#include "teleop/common/output_file.h"
#include "teleop/common/version.h"
#include "teleop/runtime/architecture.h"
#include "teleop/runtime/command_line_hint.h"
#include "teleop/runtime/realtime.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/runtime/status_names.h"
#include "teleop/runtime/trace_recorder.h"
#include "teleop/transport/participant_config.h"
#include "trace_file.h"
#include "trace_stream.h"

namespace teleop::runtime {
namespace {

struct CommandLine {
  std::string config_path;
  std::optional<double> duration_s;
  std::optional<int> domain_id;
  std::string report_path;
  std::string log_level = "info";
  std::vector<std::string> impair;
  std::optional<uint64_t> seed;
  std::vector<std::string> sets;
  std::string trace_path;
  std::optional<double> trace_seconds;
  bool trace_stream = false;
};

// "--impair PEER=PROFILE": impair the link to PEER ("*": every peer) with PROFILE
void apply_impair_overrides(const CommandLine& cli, transport::ParticipantConfig& transport) {
  for (const std::string& spec : cli.impair) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0) throw ConfigError("--impair " + spec + ": expected PEER=PROFILE");
    const std::string peer = spec.substr(0, eq);
    const std::string profile = spec.substr(eq + 1);
    const std::string path = transport::impairment::resolve_profile_path(profile, cli.config_path);
    if (path.empty()) throw ConfigError("--impair " + spec + ": no profile file '" + profile + "'");
    auto& links = transport.impairment.links;
    std::erase_if(links, [&](const auto& l) { return l.to == peer; });
    links.push_back({peer, transport::impairment::load_link_profile(path)});
  }
  if (cli.seed) transport.impairment.seed = *cli.seed;
}

std::string format_number(double v) {
  std::ostringstream out;
  out << std::setprecision(15) << v;
  return out.str();
}

// what a numeric flag may be: a finite number in [min, max] (NaN and infinity never configure anything)
CLI::Validator finite_in(double min, double max) {
  const std::string range = "[" + format_number(min) + ", " + format_number(max) + "]";
  return CLI::Validator(
      [min, max, range](const std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < min || v > max) {
          return "must be a finite number in " + range + ", got " + text;
        }
        return {};
      },
      "NUMBER in " + range);
}

// the trace is preallocated for its whole window: a bound on its rows keeps a long run's
// --trace from claiming the machine's memory (4e6 rows: 66 min at 1 kHz, ~1 GB at 30 columns)
constexpr uint64_t kMaxTraceRows = 4'000'000;

uint64_t trace_rows(const CommandLine& cli, const NodeConfig& node) {
  const double seconds = cli.trace_seconds.value_or(node.duration_s > 0 ? node.duration_s : 60.0);
  const double rows = std::ceil(seconds * node.rate_hz) + 1;
  if (rows > static_cast<double>(kMaxTraceRows)) {
    throw ConfigError("--trace-seconds: a trace of " + format_number(seconds) + " s at " + format_number(node.rate_hz) +
                      " Hz needs " + format_number(rows) + " rows; it keeps at most " + format_number(kMaxTraceRows) +
                      ": give a shorter --trace-seconds (with --trace-stream the file gets every row anyway)");
  }
  return static_cast<uint64_t>(rows);
}

// everything parsed and validated before anything touches the network
struct Setup {
  NodeConfig node;
  transport::ParticipantConfig transport;
  LogicBuilder build;
  /// The teleoperation architecture the node plays (its `teleoperation:` section); empty: none.
  std::string architecture;
};

Setup load_setup(const CommandLine& cli, const NodeDescription& description) {
  spdlog::debug("reading the configuration {}", cli.config_path);
  ConfigNode root = ConfigNode::load_file(cli.config_path);
  for (const std::string& spec : cli.sets) root.apply_override(spec);
  Setup setup{parse_node_config(root.child("node"), description.role_name), {}, {}};
  setup.transport = transport::parse_participant_config(root.child("transport"), setup.node.name);
  setup.transport.warn_same_name = true;
  setup.build = description.parse(root);
  if (const auto teleoperation = parse_teleoperation_config(root)) setup.architecture = teleoperation->architecture->name;
  root.check_all_used();
  if (cli.duration_s) setup.node.duration_s = *cli.duration_s;
  if (cli.domain_id) setup.transport.domain_id = *cli.domain_id;
  apply_impair_overrides(cli, setup.transport);
  if (!cli.trace_path.empty()) trace_rows(cli, setup.node);
  // where the results go, before the node joins the network: a path that cannot be written is an
  // error now, not a result lost at the end
  if (!cli.report_path.empty()) check_output_file(cli.report_path, "--report");
  if (!cli.trace_path.empty()) check_output_file(cli.trace_path, "--trace");
  return setup;
}

void log_summary(const NodeReport& r) {
  spdlog::info("{}: {} cycles at {:.0f} Hz, {} overruns, {} skipped, lateness p50 {:.1f} us p99 {:.1f} us max {:.1f} us",
               r.name, r.cycles, r.rate_hz, r.overruns, r.skipped, r.lateness_p50_ns * 1e-3,
               r.lateness_p99_ns * 1e-3, r.lateness_max_ns * 1e-3);
  for (const auto& l : r.links) {
    spdlog::info("{}: link to {} ({}, seed {}): {} messages, {} lost, {} in outages, {} queue drops, {} duplicated, "
                 "{} reordered, added delay p50 {:.2f} ms p99 {:.2f} ms",
                 r.name, l.to, l.profile, r.impairment_seed, l.messages, l.lost, l.outage, l.queue, l.duplicated,
                 l.reordered, l.delay_p50_ns * 1e-6, l.delay_p99_ns * 1e-6);
  }
  for (const auto& t : r.received) {
    spdlog::info("{}: {} received {} of {} ({} lost), {:.1f} Hz, latency p50 {:.1f} us p99 {:.1f} us", r.name, t.topic,
                 t.received, t.expected, t.lost, t.rate_hz, t.latency_p50_ns * 1e-3, t.latency_p99_ns * 1e-3);
  }
}

// the trace recorder when --trace asks for one and the logic has columns; sized for the most recent
// --trace-seconds (default: the run's duration, else 60 s)
std::unique_ptr<TraceRecorder> make_trace_recorder(const CommandLine& cli, const NodeConfig& node,
                                                   const NodeLogic& logic) {
  if (cli.trace_path.empty()) return nullptr;
  std::vector<std::string> columns;
  logic.trace_columns(columns);
  if (columns.empty()) {
    spdlog::info("{}: this node has no trace columns: --trace {} writes nothing", node.name, cli.trace_path);
    return nullptr;
  }
  const uint64_t rows = trace_rows(cli, node);
  spdlog::info("{}: tracing {} columns, the most recent {} rows ({:.1f} s), into {}", node.name, columns.size(), rows,
               static_cast<double>(rows - 1) / node.rate_hz, cli.trace_path);
  return std::make_unique<TraceRecorder>(std::move(columns), rows);
}

// writes what the trace still holds (streamed: its last rows; else the whole CSV) and counts in the
// report the rows in the file and those that never got there; false when a write failed (logged
// when it happened: by the stream's writer, or here)
bool finish_trace(const CommandLine& cli, const NodeConfig& node, const TraceRecorder& trace, TraceStream* stream,
                  NodeReport& report) {
  uint64_t written = 0;
  bool ok = true;
  if (stream != nullptr) {
    ok = stream->stop();
    written = stream->rows_written();
  } else {
    try {
      const TraceFileResult result = write_held_rows(trace, cli.trace_path);
      written = result.rows_written;
      ok = result.error.empty();
      if (!ok) spdlog::error("{}: trace {}: write failed ({})", node.name, cli.trace_path, result.error);
    } catch (const std::runtime_error& e) {
      spdlog::error("{}: {}", node.name, e.what());
      ok = false;
    }
  }
  const uint64_t dropped = trace.rows_complete() - written;
  report.counters.emplace_back("trace_rows_written", static_cast<double>(written));
  report.counters.emplace_back("trace_rows_dropped", static_cast<double>(dropped));
  spdlog::info("{}: wrote {} trace rows ({} dropped) to {}", node.name, written, dropped, cli.trace_path);
  return ok;
}

// the fixed-rate loop; `trace` (may be null) gets one row per cycle
void run_loop(const NodeConfig& node, NodeLogic& logic, StatusPublisher& status, RatePacer& pacer,
              TraceRecorder* trace, StateWatch& state_watch) {
  const int64_t start_ns = monotonic_now_ns();
  const int64_t end_ns = node.duration_s > 0 ? start_ns + static_cast<int64_t>(node.duration_s * 1e9) : INT64_MAX;
  pacer.start();
  while (!shutdown_requested()) {
    const CycleTick tick = pacer.wait_next();
    // at the release, before the cycle's work: the wall time of the same instant as tick.now_ns
    const int64_t wall_ns = system_now_ns();
    if (shutdown_requested() || tick.now_ns >= end_ns) break;
    logic.cycle(tick);
    // a fortieth of the period per cycle: a 1 kHz loop moves its phase by up to 25 us a cycle
    if (const int64_t phase_ns = logic.pacing_phase_ns(); phase_ns != 0) pacer.steer_phase(phase_ns, node.period_ns() / 40);
    if (trace != nullptr) logic.trace_row(trace->begin_row({tick.now_ns, wall_ns, tick.now_ns - tick.deadline_ns}));
    const bool changed = state_watch.after_cycle(tick, logic, pacer.stats());
    status.maybe_publish(tick, logic, pacer.stats(), changed);
  }
}

// the loop's thread at its real-time priority, the middleware's threads below it and the node's
// own helpers ordinary; throws only when real time is required and refused
void enter_realtime(const NodeConfig& node) {
  if (const std::string problem = apply_realtime(node.realtime); !problem.empty()) {
    if (node.realtime.mode == RealtimeMode::kRequired) throw std::runtime_error("real-time setup: " + problem);
    spdlog::warn("{}: running without real-time scheduling: {}", node.name, problem);
    return;
  }
  if (node.realtime.mode == RealtimeMode::kOff) return;
  const ThreadCensus c = place_other_threads(node.realtime);
  spdlog::info("{}: the loop at SCHED_FIFO {}; {} middleware threads at {}, {} of its own at SCHED_OTHER{}", node.name,
               node.realtime.priority, c.middleware,
               node.realtime.dds_priority > 0 ? fmt::format("SCHED_FIFO {}", node.realtime.dds_priority)
                                              : std::string("SCHED_OTHER"),
               c.own, c.refused > 0 ? fmt::format(" ({} threads the kernel refused to move)", c.refused) : "");
}

// what a run leaves once its participant is gone
struct RunOutcome {
  NodeReport report;
  std::unique_ptr<TraceRecorder> trace;
  std::unique_ptr<TraceStream> stream;
};

// the node on the network, from creating its participant to filling the report; a signal that came
// while the participant was created ends it before the logic is built (the follower would take
// 100 ms to build its model only to delete it)
void run_on_network(const CommandLine& cli, const NodeDescription& description, const Setup& setup, RunOutcome& out) {
  const NodeConfig& node = setup.node;
  NodeReport& report = out.report;
  report.name = node.name;
  report.role = description.role_name;
  report.rate_hz = node.rate_hz;
  transport::Participant participant(setup.transport);
  spdlog::info("{}: QoS profiles from {}, {} topic names", node.name, participant.qos_profiles_source(),
               setup.transport.naming == transport::Naming::kRos2 ? "ROS 2" : "plain");
  if (shutdown_requested()) {
    report.final_state = state_name(msg::STATE_STARTING);
    return;
  }
  NodeContext context{node, participant};
  // every node honours the stop chain: its logic behind the gate that latches emergency stops
  std::unique_ptr<NodeLogic> logic =
      std::make_unique<EmergencyStopGate>(setup.build(context), participant, node.name, setup.architecture);
  out.trace = make_trace_recorder(cli, node, *logic);
  if (out.trace && cli.trace_stream) out.stream = std::make_unique<TraceStream>(*out.trace, cli.trace_path);
  StatusPublisher status(participant, node.name, description.role, setup.architecture, node.rate_hz,
                         node.status_rate_hz);
  const FlowWatch flow_watch(participant, node.name, setup.transport.domain_id);
  NodeEventLog event_log(participant.events(), node.name);
  StateWatch state_watch(participant.events());
  MonotonicClock clock;
  RatePacer pacer(clock, node.period_ns(), node.max_catch_up_cycles);

  enter_realtime(node);
  // every endpoint exists now: announce them a few times over, for peers behind a lossy link
  participant.boost_discovery();
  const int64_t started_ns = monotonic_now_ns();
  run_loop(node, *logic, status, pacer, out.trace.get(), state_watch);
  if (out.trace) out.trace->finish();
  // bounded, so that shutdown stays well inside 100 ms even with a dead status reader
  status.publish_stopping(*logic, pacer.stats(), 50 * kNsPerMs);

  report.final_state = state_name(logic->state());
  report.run_time_s = static_cast<double>(monotonic_now_ns() - started_ns) * 1e-9;
  report.add_loop(pacer.stats());
  logic->fill_report(report);
  report.add_links(participant);
}  // the participant and all its entities are deleted here

int run(const CommandLine& cli, const NodeDescription& description) {
  const Setup setup = load_setup(cli, description);
  const NodeConfig& node = setup.node;
  spdlog::info("{}: starting ({} Hz, domain {}, {}{}, discovery {}, security {})", node.name, node.rate_hz,
               setup.transport.domain_id, setup.transport.udpv4 ? "udpv4" : "", setup.transport.shm ? " shm" : "",
               transport::discovery_mode_name(setup.transport.discovery),
               setup.transport.security.enabled() ? "on" : "off");
  // from here a signal raises the flag: the participant must be deleted, the report written
  set_signals_exit_at_once(false);
  RunOutcome out;
  run_on_network(cli, description, setup, out);
  NodeReport& report = out.report;
  if (const int64_t signalled = shutdown_requested_at_ns(); signalled > 0) {
    report.shutdown_ms = static_cast<double>(monotonic_now_ns() - signalled) * 1e-6;
    spdlog::info("{}: shut down {:.1f} ms after the signal", node.name, report.shutdown_ms);
  }
  // after the loop and the shutdown measurement: writing is slow and never on the control path;
  // before the report, which counts the rows that reached the file (a failed write costs no report)
  const bool trace_written = out.trace == nullptr || finish_trace(cli, node, *out.trace, out.stream.get(), report);
  log_summary(report);
  if (!cli.report_path.empty()) write_report(report, cli.report_path);
  return trace_written ? 0 : 1;
}

}  // namespace

int run_node(int argc, char** argv, const NodeDescription& description) {
  CLI::App app{description.summary, "teleop_" + description.role_name};
  app.set_version_flag("--version", teleop::version_text());
  CommandLine cli;
  app.add_option("-c,--config", cli.config_path,
                 "YAML configuration of this node: a file, or a name in config/nodes (e.g. follower)")
      ->required();
  // the same bound as node.duration_s in the file
  app.add_option("-d,--duration", cli.duration_s, "run time in seconds (overrides node.duration_s; 0 = until signalled)")
      ->check(finite_in(0, 1e6));
  app.add_option("--domain", cli.domain_id, "DDS domain id (overrides transport.domain_id)")->check(CLI::Range(0, 232));
  app.add_option("-r,--report", cli.report_path, "write the run's statistics as YAML to this file at exit");
  app.add_option("--impair", cli.impair,
                 "impair the outgoing link to PEER (a node name, or * for all) with PROFILE (a file or a name "
                 "in config/network), e.g. --impair follower=wan-35ms; repeatable");
  app.add_option("--seed", cli.seed, "seed of the impairment decisions (default: transport.impairment.seed)");
  app.add_option("--set", cli.sets,
                 "override a config value: KEY is a dotted path, VALUE is YAML, e.g. --set node.rate_hz=500 or "
                 "--set leader.amplitudes_rad=[0,0.2,0,0.2,0,0,0]; repeatable, applied in order");
  app.add_option("--trace", cli.trace_path,
                 "write the node's time trace (CSV: t_s = CLOCK_MONOTONIC, wall_s = CLOCK_REALTIME, lateness_us, the "
                 "node's columns) to this file at exit");
  app.add_flag("--trace-stream", cli.trace_stream,
               "write the trace while running (a SIGKILL or crash loses at most its last 50 ms), not at exit");
  app.add_option("--trace-seconds", cli.trace_seconds,
                 "keep the most recent S seconds of trace (default: the run's duration, else 60)")
      ->check(finite_in(1e-3, 1e6));
  app.add_option("--log-level", cli.log_level, "trace, debug, info, warn, error")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return exit_after_parse_error(app, e, argc, argv);
  }
  spdlog::set_level(spdlog::level::from_str(cli.log_level));
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  // until the node joins the network a signal ends it at once: parsing a large config or compiling
  // a model polls no flag (run() switches this off before the participant)
  set_signals_exit_at_once(true);
  install_shutdown_handlers();
  // wake up at the deadline, not up to 50 us later (the kernel's default timer slack)
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  try {
    // a shipped configuration by name works from any folder, installed or in a build tree
    cli.config_path = resolve_config("nodes", cli.config_path);
    return run(cli, description);
  } catch (const ConfigError& e) {
    spdlog::error("config error: {}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", description.role_name, e.what());
    return 1;
  }
}

}  // namespace teleop::runtime
