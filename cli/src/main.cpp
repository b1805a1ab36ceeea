// teleop: command-line entry point. `teleop launch demo` (a scenario's name or file) runs it, `teleop sweep`
// one scenario under several network profiles, `teleop experiment` runs x profiles with metrics,
// `teleop reset NODE` clears a node's latched reflex, `teleop estop`/`enable` (operator_request_commands.h), `teleop plot RUN_DIR` draws a run's figures,
// `teleop hand-study STUDY.yaml` reproduces the SVH hand study in MuJoCo (hand_study_command.h),
// `teleop fidelity-study STUDY.yaml` the coupling thesis's twin accuracy and wiping studies (fidelity_study_command.h);
// `teleop topic`, `monitor`, `record`, `replay` (bus_commands.h) look at and keep the bus,
// `teleop bag info|convert|repair|export` (bag_commands.h) handle recordings;
// `teleop doctor` checks this host for a 1 kHz node (doctor_command.h);
// `teleop view` shows the robot live, `teleop render RUN_DIR` makes a video of a run (view_command.h).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "teleop/common/config.h"
#include "teleop/common/version.h"
#include "teleop/experiment/experiment_runner.h"
#include "teleop/experiment/results_table.h"
#include "teleop/experiment/network_sweep.h"
#include "teleop/experiment/soak.h"
#include "teleop/launcher/launcher.h"
#include "teleop/runtime/command_line_hint.h"
#include "bag_commands.h"
#include "bus_commands.h"
#include "config_option.h"
#include "doctor_command.h"
#include "fidelity_study_command.h"
#include "hand_study_command.h"
#include "operator_request_commands.h"
#include "plot_command.h"
#include "view_command.h"

int main(int argc, char** argv) {
  using namespace teleop::launcher;
  CLI::App app{"teleop: teleoperation middleware tools"};
  app.set_version_flag("--version", teleop::version_text());
  app.require_subcommand(1);
  std::string scenario_path;
  LaunchOptions options;
  CLI::App* launch_cmd = app.add_subcommand("launch", "start the nodes of a scenario, stop them together, print a summary");
  launch_cmd
      ->add_option("scenario", scenario_path, "scenario YAML file, or its name (demo: config/scenarios/demo.yaml)")
      ->required()
      ->transform(teleop::cli::named_config("scenarios"))
      ->check(CLI::ExistingFile);
  launch_cmd->add_option("-d,--duration", options.duration_s, "run time in seconds (overrides the scenario)")
      ->check(CLI::NonNegativeNumber);
  launch_cmd->add_option("--domain", options.domain_id, "DDS domain id for every node (overrides their configs)")
      ->check(CLI::Range(0, 232));
  launch_cmd->add_option("--network", options.network,
                          "network profile (name in config/network or a file) impairing every link, both directions");
  launch_cmd->add_option("--seed", options.seed, "seed of the impairment decisions (printed, so a run can be repeated)");
  launch_cmd->add_option("--report-dir", options.report_dir, "directory for the nodes' reports (default: a new one in /tmp)");
  launch_cmd->add_option("--bin-dir", options.bin_dir, "directory of the node executables (default: next to teleop)");
  launch_cmd->add_option("--set", options.sets,
                         "override a value in one node's config: NODE:KEY=VALUE, e.g. "
                         "leader:teleoperation.architecture=pfc_tdpa; repeatable");
  launch_cmd->add_option("--trace-dir", options.trace_dir, "each node writes its time trace to DIR/<node>.csv");
  std::vector<std::string> profiles;
  std::string csv_path = "sweep.csv";
  CLI::App* sweep_cmd =
      app.add_subcommand("sweep", "run a scenario once per network profile and write one combined CSV");
  sweep_cmd->add_option("scenario", scenario_path, "scenario YAML file, or its name in config/scenarios")
      ->required()
      ->transform(teleop::cli::named_config("scenarios"))
      ->check(CLI::ExistingFile);
  sweep_cmd->add_option("-p,--profiles", profiles, "network profiles (names in config/network or files; 'none' = unimpaired)")
      ->required()
      ->delimiter(',');
  sweep_cmd->add_option("--csv", csv_path, "combined results (default sweep.csv)");
  sweep_cmd->add_option("-d,--duration", options.duration_s, "run time of each run in seconds")->check(CLI::NonNegativeNumber);
  sweep_cmd->add_option("--domain", options.domain_id, "DDS domain id for every node")->check(CLI::Range(0, 232));
  sweep_cmd->add_option("--seed", options.seed, "seed of the impairment decisions");
  sweep_cmd->add_option("--report-dir", options.report_dir, "keep each run's node reports under DIR/<profile>");
  sweep_cmd->add_option("--bin-dir", options.bin_dir, "directory of the node executables");
  std::string experiment_path;
  teleop::experiment::ExperimentOptions experiment_options;
  CLI::App* experiment_cmd = app.add_subcommand(
      "experiment", "run every run x network profile of an experiment file, analyse the traces, print a table + CSV");
  experiment_cmd->add_option("experiment", experiment_path, "experiment YAML file, or its name in config/experiments")
      ->required()
      ->transform(teleop::cli::named_config("experiments"))
      ->check(CLI::ExistingFile);
  experiment_cmd->add_option("--profiles", experiment_options.profiles, "only these network profiles (comma-separated)")
      ->delimiter(',');
  experiment_cmd->add_option("--runs", experiment_options.runs, "only these runs (comma-separated names)")
      ->delimiter(',');
  experiment_cmd->add_option("-d,--duration", experiment_options.duration_s, "seconds of each run (overrides the file)")
      ->check(CLI::PositiveNumber);
  experiment_cmd->add_option("--csv", experiment_options.csv_path, "results CSV (default: <report dir>/<name>.csv)");
  experiment_cmd->add_option("--report-dir", experiment_options.report_dir,
                             "traces and node reports under DIR/<run>/<profile>/ (default: a new folder in /tmp)");
  experiment_cmd->add_option("--bin-dir", experiment_options.bin_dir, "directory of the node executables");
  experiment_cmd
      ->add_option("--domain", experiment_options.domain_id,
                   "DDS domain of the first run; each further run takes the next (default 60)")
      ->check(CLI::Range(0, 232));
  experiment_cmd
      ->add_option("--repeat", experiment_options.repeat,
                   "each run x profile N times, repeat k with seed experiment.seed + k - 1; the table adds mean ± sd")
      ->check(CLI::Range(1, 1000));
  experiment_cmd->add_flag("--no-plots{false}", experiment_options.plots,
                           "no figures (default: one per metric beside the CSV, each run's in its folder)");
  std::string soak_path;
  teleop::experiment::SoakOptions soak_options;
  CLI::App* soak_cmd = app.add_subcommand(
      "soak", "kill and restart a scenario's nodes at random under a hostile network, measure each recovery");
  soak_cmd->add_option("soak", soak_path, "soak YAML file, or its name in config/experiments (soak)")
      ->required()
      ->transform(teleop::cli::named_config("experiments"))
      ->check(CLI::ExistingFile);
  soak_cmd->add_option("--kills-per-node", soak_options.kills_per_node, "kills of each node (overrides the file)")
      ->check(CLI::Range(1, 10'000));
  soak_cmd->add_option("--seed", soak_options.seed, "seed of the kill schedule and the network (overrides the file)");
  soak_cmd->add_option("--domain", soak_options.domain_id, "DDS domain id for every node")->check(CLI::Range(0, 232));
  soak_cmd->add_option("--report-dir", soak_options.report_dir, "traces, reports and logs (default: a new folder in /tmp)");
  soak_cmd->add_option("--bin-dir", soak_options.bin_dir, "directory of the node executables");
  const teleop::cli::OperatorRequestCommands operator_requests(app);
  const teleop::cli::DoctorCommand doctor(app);
  BusCommands bus_commands(app);
  const teleop::cli::BagCommands bag_commands(app);
  const teleop::cli::PlotCommand plot(app);
  const teleop::cli::HandStudyCommand hand_study(app);
  const teleop::cli::FidelityStudyCommand fidelity_study(app);
  teleop::cli::ViewCommands view_commands(app);
  view_commands.add_experiment_option(experiment_cmd);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return teleop::runtime::exit_after_parse_error(app, e, argc, argv);
  }
  try {
    if (const auto rc = bus_commands.run()) return *rc;
    if (const auto rc = bag_commands.run()) return *rc;
    if (const auto rc = view_commands.run()) return *rc;
    if (plot.parsed()) return plot.run();
    if (hand_study.parsed()) return hand_study.run();
    if (fidelity_study.parsed()) return fidelity_study.run();
    if (const auto rc = operator_requests.run()) return *rc;
    if (const auto rc = doctor.run()) return *rc;
    if (soak_cmd->parsed()) {
      using namespace teleop::experiment;
      const SoakResult result = run_soak(load_soak(soak_path), soak_options);
      std::printf("%s", format_soak(result, soak_path).c_str());
      std::printf("\nevents: %s\ntraces, reports and logs: %s\n", result.csv_path.c_str(), result.report_dir.c_str());
      const bool unrecovered = std::any_of(result.events.begin(), result.events.end(),
                                           [](const SoakEvent& e) { return e.unrecovered(); });
      const bool failed = result.failures > 0 || unrecovered || result.stale_commands > 0 ||
                          result.torque_violations > 0 || result.reflex_violations > 0;
      if (failed) std::printf("RESULT: FAILED (a process failed, an event did not recover, or a violation)\n");
      return failed ? 1 : 0;
    }
    if (experiment_cmd->parsed()) {
      using namespace teleop::experiment;
      const ExperimentConfig config = load_experiment(experiment_path);
      const ExperimentResult result = run_experiment(config, experiment_options);
      std::printf("%s", format_table(result.rows, config.name, config.analysis.kind).c_str());
      if (result.repeats > 1) std::printf("%s", format_summary_table(result.rows, config.analysis.kind).c_str());
      std::printf("\nresults: %s\ntraces and reports: %s\n", result.csv_path.c_str(), result.report_dir.c_str());
      if (result.repeats > 1) std::printf("summary: %s\n", summary_csv_path(result.csv_path).c_str());
      if (result.failures > 0)
        std::printf("RESULT: FAILED (%d runs failed or could not be analysed, see above)\n", result.failures);
      const int unrendered = view_commands.render_experiment(result.report_dir);
      if (unrendered > 0) std::printf("RESULT: FAILED (%d runs could not be rendered, see above)\n", unrendered);
      return result.failures > 0 || unrendered > 0 ? 1 : 0;
    }
    const Scenario scenario = load_scenario(scenario_path);
    if (sweep_cmd->parsed()) return teleop::experiment::network_sweep(scenario, options, profiles, csv_path).failed_runs == 0 ? 0 : 1;
    const LaunchResult result = launch(scenario, options);
    std::printf("%s", format_summary(result.summary, scenario.name).c_str());
    std::printf("\nreports: %s\n", result.report_dir.c_str());
    if (result.exit_code != 0) std::printf("RESULT: FAILED (a node failed to start, run or stop cleanly; see above)\n");
    return result.exit_code;
  } catch (const teleop::ConfigError& e) {
    std::fprintf(stderr, "config error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "teleop %s: %s\n", app.get_subcommands().front()->get_name().c_str(), e.what());
    return 1;
  }
}
