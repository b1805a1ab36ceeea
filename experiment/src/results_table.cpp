#include "teleop/experiment/results_table.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

namespace teleop::experiment {
namespace {

constexpr double kNaN = RunMetrics::kNone;

// one metric column: its heading in the table, its name in the CSV and how to read it off a row
// (NaN: the row has no sample for it); a flag reads 1 or 0 and shows as yes/no
struct Column {
  const char* heading;
  const char* csv_name;
  std::function<double(const RunRow&)> value;
  bool flag = false;
};

Column mad_column() { return {"mad_rad", "mad_rad", [](const RunRow& r) { return r.metrics.mad_rad; }}; }

// the passivity and safety signals every task reports, last in the row
std::vector<Column> safety_columns() {
  return {
      {"tdpa_J", "tdpa_min_energy_j", [](const RunRow& r) { return r.metrics.tdpa_min_energy_j; }},
      {"sat", "saturation_fraction", [](const RunRow& r) { return r.metrics.saturation_fraction; }},
      {"hold", "safe_hold_fraction", [](const RunRow& r) { return r.metrics.safe_hold_fraction; }},
  };
}

std::vector<Column> stiff_wall_columns() {
  std::vector<Column> c = {
      {"f_err_N", "force_error_n", [](const RunRow& r) { return r.metrics.force_error_n; }},
      {"f_felt_N", "force_felt_n", [](const RunRow& r) { return r.metrics.force_felt_n; }},
      {"f_ext_N", "force_exerted_n", [](const RunRow& r) { return r.metrics.force_exerted_n; }},
      {"track_m", "tracking_rmse_m", [](const RunRow& r) { return r.metrics.tracking_rmse_m; }},
      {"track_hold", "tracking_hold_m", [](const RunRow& r) { return r.metrics.tracking_hold_m; }},
      mad_column(),
      {"f_mad_N", "force_mad_n", [](const RunRow& r) { return r.metrics.force_mad_n; }},
      {"ptp_m", "hold_ptp_m", [](const RunRow& r) { return r.metrics.hold_ptp_m; }},
  };
  for (Column& safety : safety_columns()) c.push_back(std::move(safety));
  return c;
}

// a box-task metric of the row, NaN when its traces were not analysed
double box(const RunRow& r, const std::function<double(const box_task::BoxTaskMetrics&)>& get) {
  return r.box_task ? get(*r.box_task) : kNaN;
}

std::vector<Column> box_task_columns() {
  using M = box_task::BoxTaskMetrics;
  std::vector<Column> c = {
      {"success", "success", [](const RunRow& r) { return box(r, [](const M& m) { return m.success ? 1.0 : 0.0; }); }, true},
      {"time_s", "task_time_s", [](const RunRow& r) { return box(r, [](const M& m) { return m.task_time_s; }); }},
      {"carry_s", "carry_time_s", [](const RunRow& r) { return box(r, [](const M& m) { return m.carry_time_s; }); }},
      {"sq_var_L", "squeeze_variation_left_n", [](const RunRow& r) { return box(r, [](const M& m) { return m.squeeze_variation_n[0]; }); }},
      {"sq_var_R", "squeeze_variation_right_n", [](const RunRow& r) { return box(r, [](const M& m) { return m.squeeze_variation_n[1]; }); }},
      {"sq_min_L", "squeeze_min_left_n", [](const RunRow& r) { return box(r, [](const M& m) { return m.squeeze_min_n[0]; }); }},
      {"sq_min_R", "squeeze_min_right_n", [](const RunRow& r) { return box(r, [](const M& m) { return m.squeeze_min_n[1]; }); }},
      {"slip_mm", "slip_mm", [](const RunRow& r) { return box(r, [](const M& m) { return m.slip_mm; }); }},
      {"dropped", "dropped", [](const RunRow& r) { return box(r, [](const M& m) { return m.dropped ? 1.0 : 0.0; }); }, true},
      {"collide_N", "max_arm_collision_n", [](const RunRow& r) { return box(r, [](const M& m) { return m.max_arm_collision_n; }); }},
      mad_column(),
  };
  for (Column& safety : safety_columns()) c.push_back(std::move(safety));
  return c;
}

std::vector<Column> columns(AnalysedTask kind) {
  return kind == AnalysedTask::kBoxTask ? box_task_columns() : stiff_wall_columns();
}

size_t width(const Column& c) { return std::max<size_t>(std::strlen(c.heading), 8); }

// a metric for the table: 4 significant digits (a flag: yes/no), "-" without samples
std::string cell(const Column& c, double value) {
  if (std::isnan(value)) return "-";
  return c.flag ? (value != 0.0 ? "yes" : "no") : fmt::format("{:.4g}", value);
}

// a metric for the CSV: full precision (a flag: yes/no), empty without samples
std::string csv_cell(const Column& c, double value) {
  if (std::isnan(value)) return "";
  return c.flag ? (value != 0.0 ? "yes" : "no") : fmt::format("{:.9g}", value);
}

// RFC 4180: quote a field holding a comma, a quote or a line break
std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string stable_word(const Verdict& v) { return !v.stable ? "n/a" : (*v.stable ? "yes" : "no"); }

// the reasons for "unstable" and the errors, one line each
std::string notes(const std::vector<RunRow>& rows) {
  std::string out;
  for (const auto& r : rows) {
    if (!r.verdict.why.empty()) out += fmt::format("  {} / {}: stable {}: {}\n", r.run, r.profile, stable_word(r.verdict), r.verdict.why);
    if (!r.note.empty()) out += fmt::format("  {} / {}: {}: {}\n", r.run, r.profile, r.status, r.note);
  }
  return out;
}

}  // namespace

std::string format_table(const std::vector<RunRow>& rows, const std::string& title, AnalysedTask kind) {
  const std::vector<Column> metrics = columns(kind);
  std::string out = "\n== teleop experiment: " + title + " ==\n\n";
  out += fmt::format("{:<17} {:<15} {:<6} {:<6}", "run", "profile", "status", "stable");
  for (const Column& c : metrics) out += fmt::format(" {:>{}}", c.heading, width(c));
  out += "\n";
  for (const auto& r : rows) {
    out += fmt::format("{:<17} {:<15} {:<6} {:<6}", r.run, r.profile, r.status, stable_word(r.verdict));
    for (const Column& c : metrics) out += fmt::format(" {:>{}}", cell(c, c.value(r)), width(c));
    out += "\n";
  }
  const std::string why = notes(rows);
  if (!why.empty()) out += "\n" + why;
  return out;
}

std::string format_csv(const std::vector<RunRow>& rows, AnalysedTask kind) {
  const std::vector<Column> metrics = columns(kind);
  std::string out = "run,profile,status,stable,stable_why";
  for (const Column& c : metrics) out += std::string(",") + c.csv_name;
  out += ",trace_dir,note\n";
  for (const auto& r : rows) {
    out += csv_text(r.run) + "," + csv_text(r.profile) + "," + r.status + "," +
           (r.verdict.stable ? (*r.verdict.stable ? "yes" : "no") : "") + "," + csv_text(r.verdict.why);
    for (const Column& c : metrics) out += "," + csv_cell(c, c.value(r));
    out += "," + csv_text(r.trace_dir) + "," + csv_text(r.note) + "\n";
  }
  return out;
}

}  // namespace teleop::experiment
