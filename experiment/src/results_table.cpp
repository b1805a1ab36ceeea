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
      {"reflex", "reflex_latches", [](const RunRow& r) { return r.metrics.reflex_latches; }},
      {"match_s", "flows_matched_s", [](const RunRow& r) { return r.metrics.flows_matched_s; }},
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
      {"peak_N", "impact_peak_n", [](const RunRow& r) { return r.metrics.impact_peak_n; }},
      {"over", "overshoot_fraction", [](const RunRow& r) { return r.metrics.overshoot_fraction; }},
      {"settle_s", "settle_time_s", [](const RunRow& r) { return r.metrics.settle_time_s; }},
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

bool repeated(const std::vector<RunRow>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const RunRow& r) { return r.repeat > 1; });
}

// the profile, and which repeat when the cells were repeated
std::string profile_cell(const RunRow& r, bool repeats) {
  return repeats ? r.profile + " r" + std::to_string(r.repeat) : r.profile;
}

// the width of the run and profile columns: their longest cell, at least as wide as before
struct NameWidths {
  size_t run = 17;
  size_t profile = 15;
};
NameWidths name_widths(const std::vector<RunRow>& rows, bool repeats) {
  NameWidths w;
  for (const RunRow& r : rows) {
    w.run = std::max(w.run, r.run.size());
    w.profile = std::max(w.profile, profile_cell(r, repeats).size());
  }
  return w;
}

// the rows of one run x profile, in the order the first of each appears
std::vector<std::vector<const RunRow*>> cells_of(const std::vector<RunRow>& rows) {
  std::vector<std::vector<const RunRow*>> cells;
  for (const RunRow& r : rows) {
    const auto same = [&](const auto& cell) { return cell.front()->run == r.run && cell.front()->profile == r.profile; };
    const auto it = std::find_if(cells.begin(), cells.end(), same);
    if (it == cells.end()) {
      cells.push_back({&r});
    } else {
      it->push_back(&r);
    }
  }
  return cells;
}

// a metric over the ok repeats of a cell that have it
struct Spread {
  size_t n = 0;
  double mean = kNaN;
  double sd = kNaN;  // sample standard deviation, NaN below two values
  size_t yes = 0;    // a flag's
};

Spread spread_of(const Column& c, const std::vector<const RunRow*>& cell) {
  std::vector<double> values;
  for (const RunRow* r : cell) {
    const double v = c.value(*r);
    if (r->status == "ok" && !std::isnan(v)) values.push_back(v);
  }
  Spread s;
  s.n = values.size();
  if (s.n == 0) return s;
  double sum = 0;
  for (double v : values) {
    sum += v;
    s.yes += v != 0.0 ? 1 : 0;
  }
  s.mean = sum / static_cast<double>(s.n);
  if (s.n < 2) return s;
  double squares = 0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.sd = std::sqrt(squares / static_cast<double>(s.n - 1));
  return s;
}

size_t count_if_rows(const std::vector<const RunRow*>& cell, const std::function<bool(const RunRow&)>& met) {
  return static_cast<size_t>(std::count_if(cell.begin(), cell.end(), [&](const RunRow* r) { return met(*r); }));
}
size_t ok_count(const std::vector<const RunRow*>& cell) {
  return count_if_rows(cell, [](const RunRow& r) { return r.status == "ok"; });
}
size_t stable_count(const std::vector<const RunRow*>& cell) {
  return count_if_rows(cell, [](const RunRow& r) { return r.status == "ok" && r.verdict.stable.value_or(false); });
}

// a metric's summary for the table: "mean±sd" (4 significant digits), "k/n" for a flag, "-" without values
std::string spread_cell(const Column& c, const Spread& s) {
  if (s.n == 0) return "-";
  if (c.flag) return fmt::format("{}/{}", s.yes, s.n);
  return std::isnan(s.sd) ? fmt::format("{:.4g}", s.mean) : fmt::format("{:.3g}±{:.2g}", s.mean, s.sd);
}

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
  const bool repeats = repeated(rows);
  const NameWidths w = name_widths(rows, repeats);
  out += fmt::format("{:<{}} {:<{}} {:<7} {:<6}", "run", w.run, "profile", w.profile, "status", "stable");
  for (const Column& c : metrics) out += fmt::format(" {:>{}}", c.heading, width(c));
  out += "\n";
  for (const auto& r : rows) {
    out += fmt::format("{:<{}} {:<{}} {:<7} {:<6}", r.run, w.run, profile_cell(r, repeats), w.profile, r.status,
                       stable_word(r.verdict));
    for (const Column& c : metrics) out += fmt::format(" {:>{}}", cell(c, c.value(r)), width(c));
    out += "\n";
  }
  const std::string why = notes(rows);
  if (!why.empty()) out += "\n" + why;
  return out;
}

std::string format_csv(const std::vector<RunRow>& rows, AnalysedTask kind) {
  const std::vector<Column> metrics = columns(kind);
  std::string out = "run,profile,repeat,seed,status,stable,stable_why";
  for (const Column& c : metrics) out += std::string(",") + c.csv_name;
  out += ",trace_dir,note\n";
  for (const auto& r : rows) {
    out += csv_text(r.run) + "," + csv_text(r.profile) + "," + std::to_string(r.repeat) + "," + std::to_string(r.seed) +
           "," + r.status + "," +
           (r.verdict.stable ? (*r.verdict.stable ? "yes" : "no") : "") + "," + csv_text(r.verdict.why);
    for (const Column& c : metrics) out += "," + csv_cell(c, c.value(r));
    out += "," + csv_text(r.trace_dir) + "," + csv_text(r.note) + "\n";
  }
  return out;
}

std::string format_summary_table(const std::vector<RunRow>& rows, AnalysedTask kind) {
  const std::vector<Column> metrics = columns(kind);
  std::string out = "\nmean ± sample standard deviation over the ok repeats of each run x profile\n\n";
  const NameWidths w = name_widths(rows, false);
  out += fmt::format("{:<{}} {:<{}} {:>5} {:>6}", "run", w.run, "profile", w.profile, "ok", "stable");
  for (const Column& c : metrics) out += fmt::format(" {:>{}}", c.heading, width(c) + 4);
  out += "\n";
  for (const auto& cell : cells_of(rows)) {
    out += fmt::format("{:<{}} {:<{}} {:>5} {:>6}", cell.front()->run, w.run, cell.front()->profile, w.profile,
                       fmt::format("{}/{}", ok_count(cell), cell.size()), fmt::format("{}/{}", stable_count(cell), ok_count(cell)));
    for (const Column& c : metrics) out += fmt::format(" {:>{}}", spread_cell(c, spread_of(c, cell)), width(c) + 4);
    out += "\n";
  }
  return out;
}

std::string format_summary_csv(const std::vector<RunRow>& rows, AnalysedTask kind) {
  const std::vector<Column> metrics = columns(kind);
  std::string out = "run,profile,repeats,ok,stable";
  for (const Column& c : metrics) out += fmt::format(",{}_mean,{}_sd", c.csv_name, c.csv_name);
  out += "\n";
  for (const auto& cell : cells_of(rows)) {
    out += csv_text(cell.front()->run) + "," + csv_text(cell.front()->profile) + "," + std::to_string(cell.size()) +
           "," + std::to_string(ok_count(cell)) + "," + std::to_string(stable_count(cell));
    for (const Column& c : metrics) {
      const Spread s = spread_of(c, cell);
      out += "," + (s.n == 0 ? std::string() : fmt::format("{:.9g}", s.mean)) + "," +
             (std::isnan(s.sd) ? std::string() : fmt::format("{:.9g}", s.sd));
    }
    out += "\n";
  }
  return out;
}

std::string summary_csv_path(const std::string& csv_path) {
  const std::string suffix = ".csv";
  const bool csv = csv_path.size() >= suffix.size() && csv_path.compare(csv_path.size() - suffix.size(), suffix.size(), suffix) == 0;
  return (csv ? csv_path.substr(0, csv_path.size() - suffix.size()) : csv_path) + "_summary.csv";
}

}  // namespace teleop::experiment
