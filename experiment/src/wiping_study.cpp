// The wiping study's sweep (its cells in worker processes, sweep_workers.h) and its outputs.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "report_files.h"
#include "sweep_workers.h"
#include "teleop/experiment/plots.h"
#include "teleop/experiment/wiping_study.h"

namespace teleop::experiment {
namespace {

// a cell as one line of numbers for the trip from its worker ('|' then the error, newlines
// made spaces); every double in full precision, so the parent's table is the worker's
std::string encode(const WipingCell& c) {
  std::ostringstream o;
  o.precision(17);
  const auto joints = [&](const control::JointVector& v) {
    for (int i = 0; i < control::kDof; ++i) o << ' ' << v[i];
  };
  o << c.wiper_angle_rad << ' ' << c.panel_height_m << ' ' << c.sim_time_s << ' ' << c.wall_time_s << ' '
    << c.mujoco_warnings << ' ' << c.wipes.size();
  for (const WipeOutcome& w : c.wipes) {
    o << ' ' << w.contact << ' ' << w.contact_steps << ' ' << w.peak_force_n << ' ' << w.mean_force_n;
    joints(w.tau_ext_peak_nm);
    joints(w.constraint_peak_nm);
  }
  joints(c.free_tau_ext_peak_nm);
  std::string error = c.error;
  for (char& ch : error) ch = (ch == '\n' || ch == '\r') ? ' ' : ch;
  o << '|' << error;
  return o.str();
}

WipingCell decode(const std::string& line) {
  WipingCell c;
  const size_t bar = line.find('|');
  std::istringstream in(line.substr(0, bar));
  const auto joints = [&](control::JointVector& v) {
    for (int i = 0; i < control::kDof; ++i) in >> v[i];
  };
  size_t wipes = 0;
  in >> c.wiper_angle_rad >> c.panel_height_m >> c.sim_time_s >> c.wall_time_s >> c.mujoco_warnings >> wipes;
  c.wipes.resize(wipes);
  for (WipeOutcome& w : c.wipes) {
    in >> w.contact >> w.contact_steps >> w.peak_force_n >> w.mean_force_n;
    joints(w.tau_ext_peak_nm);
    joints(w.constraint_peak_nm);
  }
  joints(c.free_tau_ext_peak_nm);
  c.error = bar == std::string::npos ? "a worker's line without its end" : line.substr(bar + 1);
  // a number the stream cannot read back (a NaN or Inf of a cell gone wrong) fails the whole line:
  // never zeros passed off as measured
  if (in.fail() || !(in >> std::ws).eof()) c.error = "a worker's line that does not read back: " + line;
  return c;
}

std::string timing_csv(const WipingStudyResult& r) {
  std::ostringstream o;
  o.precision(6);
  o << "wiper_angle_rad,panel_height_m,sim_time_s,wall_time_s,rt_factor\n";
  for (const WipingCell& c : r.cells) {
    o << c.wiper_angle_rad << ',' << c.panel_height_m << ',' << c.sim_time_s << ',' << c.wall_time_s << ','
      << (c.wall_time_s > 0 ? c.sim_time_s / c.wall_time_s : 0.0) << '\n';
  }
  o << "sweep,jobs=" << r.jobs << ",," << r.wall_time_s << ",\n";
  return o.str();
}

template <typename Part>
void join_traces(const std::string& path, size_t cells, const Part& part) {
  std::ofstream out(path);
  out << kWipingTraceColumns << '\n';
  for (size_t i = 0; i < cells; ++i) {
    std::ifstream in(part(i));
    if (in) out << in.rdbuf();
    in.close();
    std::filesystem::remove(part(i));
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::vector<WipingCell> run_wiping_sweep(const WipingStudyConfig& config, const std::string& trace_csv) {
  std::vector<std::pair<double, double>> grid;
  for (double angle : config.wiper_angle.values) {
    for (double height : config.panel_height.values) grid.emplace_back(angle, height);
  }
  // each cell's trace in a part file of its own beside the result, joined in grid order below
  const auto part = [&](size_t i) {
    return trace_csv.empty() ? std::string() : trace_csv + ".cell" + std::to_string(i);
  };
  const std::vector<std::string> lines = run_in_workers(grid.size(), config.jobs, [&](size_t i) {
    return encode(run_wiping_cell(config, grid[i].first, grid[i].second, part(i)));
  });
  if (!trace_csv.empty()) join_traces(trace_csv, grid.size(), part);
  std::vector<WipingCell> cells;
  for (size_t i = 0; i < grid.size(); ++i) {
    if (lines[i].empty()) {
      WipingCell died;
      died.wiper_angle_rad = grid[i].first;
      died.panel_height_m = grid[i].second;
      died.error = "the worker died";
      cells.push_back(died);
    } else {
      cells.push_back(decode(lines[i]));
    }
  }
  return cells;
}

bool WipingStudyResult::sound() const {
  for (const WipingCell& c : cells) {
    if (!c.error.empty() || c.mujoco_warnings > 0) return false;
  }
  return true;
}

WipingStudyResult run_wiping_study(WipingStudyConfig config, const WipingStudyOptions& options) {
  if (options.jobs > 0) config.jobs = options.jobs;
  WipingStudyResult result;
  result.jobs = config.jobs;
  result.out_dir = make_report_dir(options.out_dir, "teleop-wiping-" + config.name + "-");
  result.trace_csv = result.out_dir + "/wiping_trace.csv";
  const auto start = std::chrono::steady_clock::now();
  result.cells = run_wiping_sweep(config, result.trace_csv);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  result.wipes_csv = result.out_dir + "/wiping_wipes.csv";
  result.timing_csv = result.out_dir + "/wiping_timing.csv";
  result.markdown = result.out_dir + "/wiping.md";
  write_text(result.wipes_csv, format_wiping_csv(result.cells));
  write_text(result.timing_csv, timing_csv(result));
  write_text(result.markdown, format_wiping_markdown(config, result.cells));
  if (options.plots) {
    try {
      plot_wiping_study(find_plot_tool(), result.wipes_csv, result.trace_csv, result.out_dir);
    } catch (const PlotError& e) {
      result.plot_error = e.what();
    }
  }
  return result;
}

}  // namespace teleop::experiment
