#include "teleop/experiment/results_table.h"

#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace teleop::experiment {
namespace {

// a metric for the table: 4 significant digits, "-" without samples
std::string cell(double value) { return std::isnan(value) ? "-" : fmt::format("{:.4g}", value); }

// a metric for the CSV: full precision, empty without samples
std::string csv_number(double value) { return std::isnan(value) ? "" : fmt::format("{:.9g}", value); }

// RFC 4180: quote a field holding a comma, a quote or a line break
std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string stable_word(const Verdict& v) { return !v.stable ? "n/a" : (*v.stable ? "yes" : "no"); }

std::vector<double> values(const RunMetrics& m) {
  return {m.force_error_n, m.force_felt_n, m.force_exerted_n,   m.tracking_rmse_m,     m.tracking_hold_m,
          m.mad_rad,       m.force_mad_n,  m.hold_ptp_m,          m.tdpa_min_energy_j,   m.saturation_fraction,
          m.safe_hold_fraction};
}

}  // namespace

std::string format_table(const std::vector<RunRow>& rows, const std::string& title) {
  std::string out = "\n== teleop experiment: " + title + " ==\n\n";
  out += fmt::format("{:<17} {:<15} {:<6} {:<6} {:>8} {:>8} {:>8} {:>9} {:>10} {:>9} {:>9} {:>8} {:>9} {:>6} {:>6}\n",
                     "run", "profile", "status", "stable", "f_err_N", "f_felt_N", "f_ext_N", "track_m", "track_hold",
                     "mad_rad", "f_mad_N", "ptp_m", "tdpa_J", "sat", "hold");
  for (const auto& r : rows) {
    const RunMetrics& m = r.metrics;
    out += fmt::format("{:<17} {:<15} {:<6} {:<6} {:>8} {:>8} {:>8} {:>9} {:>10} {:>9} {:>9} {:>8} {:>9} {:>6} {:>6}\n",
                       r.run, r.profile, r.status, stable_word(r.verdict), cell(m.force_error_n), cell(m.force_felt_n),
                       cell(m.force_exerted_n), cell(m.tracking_rmse_m), cell(m.tracking_hold_m), cell(m.mad_rad),
                       cell(m.force_mad_n), cell(m.hold_ptp_m), cell(m.tdpa_min_energy_j), cell(m.saturation_fraction),
                       cell(m.safe_hold_fraction));
  }
  std::string notes;
  for (const auto& r : rows) {
    if (!r.verdict.why.empty())
      notes += fmt::format("  {} / {}: stable {}: {}\n", r.run, r.profile, stable_word(r.verdict), r.verdict.why);
    if (!r.note.empty()) notes += fmt::format("  {} / {}: {}: {}\n", r.run, r.profile, r.status, r.note);
  }
  if (!notes.empty()) out += "\n" + notes;
  return out;
}

std::string format_csv(const std::vector<RunRow>& rows) {
  std::string out =
      "run,profile,status,stable,stable_why,force_error_n,force_felt_n,force_exerted_n,tracking_rmse_m,"
      "tracking_hold_m,mad_rad,force_mad_n,hold_ptp_m,tdpa_min_energy_j,saturation_fraction,safe_hold_fraction,trace_dir,note\n";
  for (const auto& r : rows) {
    out += csv_text(r.run) + "," + csv_text(r.profile) + "," + r.status + "," +
           (r.verdict.stable ? (*r.verdict.stable ? "yes" : "no") : "") + "," + csv_text(r.verdict.why);
    for (double v : values(r.metrics)) out += "," + csv_number(v);
    out += "," + csv_text(r.trace_dir) + "," + csv_text(r.note) + "\n";
  }
  return out;
}

}  // namespace teleop::experiment
