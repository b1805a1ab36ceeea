#include "teleop/experiment/network_sweep.h"

#include <spdlog/fmt/fmt.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace teleop::experiment {

using launcher::LaunchOptions;
using launcher::RunSummary;
using launcher::Scenario;
using launcher::TopicFlow;

namespace {

// the sending node's impaired link that carried a flow (its own link to the receiver, else '*')
const runtime::ImpairedLink* link_of(const RunSummary& summary, const TopicFlow& flow) {
  const runtime::ImpairedLink* any = nullptr;
  for (const auto& n : summary.nodes) {
    if (n.name != flow.from) continue;
    for (const auto& l : n.links) {
      if (l.to == flow.to) return &l;
      if (l.to == "*") any = &l;
    }
  }
  return any;
}

}  // namespace

std::string csv_rows(const RunSummary& summary, const std::string& profile, bool header) {
  std::string out;
  if (header) {
    out += "profile,topic,from,to,sent,received,lost,loss_pct,rate_hz,latency_p50_ms,latency_p99_ms,latency_max_ms,"
           "age_p50_ms,age_p99_ms,miss_run_mean,miss_run_max,deadline_missed,link_configured_delay_ms,"
           "link_configured_loss_pct,link_measured_loss_pct,link_loss_burst_mean,link_outage_drops\n";
  }
  for (const auto& f : summary.flows) {
    const auto& r = f.received;
    const double loss = r.expected ? 100.0 * static_cast<double>(r.lost) / static_cast<double>(r.expected) : 0.0;
    out += fmt::format("{},{},{},{},{},{},{},{:.4f},{:.2f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.3f},{},{}", profile,
                       f.topic, f.from, f.to, f.sent, r.received, r.lost, loss, r.rate_hz, r.latency_p50_ns * 1e-6,
                       r.latency_p99_ns * 1e-6, r.latency_max_ns * 1e-6, r.age_p50_ns * 1e-6, r.age_p99_ns * 1e-6,
                       r.gap_mean, r.gap_max, r.deadline_missed);
    if (const runtime::ImpairedLink* l = link_of(summary, f)) {
      const double measured = l->messages ? 100.0 * static_cast<double>(l->lost) / static_cast<double>(l->messages) : 0.0;
      out += fmt::format(",{:.4f},{:.4f},{:.4f},{:.3f},{}\n", l->configured_delay_ns * 1e-6, 100.0 * l->configured_loss,
                         measured, l->loss_burst_mean, l->outage);
    } else {
      out += ",0,0,0,0,0\n";
    }
  }
  return out;
}

NetworkSweepResult network_sweep(const Scenario& scenario, const LaunchOptions& base, const std::vector<std::string>& profiles,
                  const std::string& csv_path) {
  std::ofstream csv(csv_path);
  if (!csv) throw std::runtime_error("cannot write " + csv_path);
  NetworkSweepResult result;
  bool header = true;
  for (const auto& profile : profiles) {
    std::printf("\n[sweep   ] === profile %s ===\n", profile.c_str());
    LaunchOptions options = base;
    options.network = profile == "none" ? "" : profile;
    // each run its own report folder under the given one
    if (!base.report_dir.empty()) options.report_dir = base.report_dir + "/" + profile;
    const launcher::LaunchResult run = launcher::launch(scenario, options);
    std::printf("%s", launcher::format_summary(run.summary, scenario.name + " / " + profile).c_str());
    if (run.exit_code != 0) ++result.failed_runs;
    csv << csv_rows(run.summary, profile, header);
    csv.flush();
    header = false;
    result.report_dirs.push_back(run.report_dir);
  }
  std::printf("\n[sweep   ] %zu runs, %d failed; combined results: %s\n", profiles.size(), result.failed_runs,
              csv_path.c_str());
  return result;
}

}  // namespace teleop::experiment
