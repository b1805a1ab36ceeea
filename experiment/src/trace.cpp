#include "teleop/experiment/trace.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "teleop/runtime/status_names.h"
#include "teleop/runtime/trace_recorder.h"

namespace teleop::experiment {
namespace {

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  size_t begin = 0;
  for (;;) {
    const auto comma = line.find(',', begin);
    cells.push_back(line.substr(begin, comma - begin));
    if (comma == std::string::npos) return cells;
    begin = comma + 1;
  }
}

// a cell as a number; empty means NaN (strtod reads "nan" and "inf" itself)
bool parse_cell(const std::string& cell, double& value) {
  if (cell.empty()) {
    value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtod(cell.c_str(), &end);
  // ERANGE also flags an underflow to a subnormal (a filtered torque decaying to 1e-308): a number;
  // only an overflow (inf) is not
  return end == cell.c_str() + cell.size() && !(errno == ERANGE && std::isinf(value));
}

// a state column's cell: the state's name (as written since the traces name their states) or its
// number (older traces); NaN for an empty cell
bool parse_state_cell(const std::string& cell, double& value) {
  if (const auto state = runtime::state_from_name(cell)) {
    value = static_cast<double>(*state);
    return true;
  }
  return parse_cell(cell, value);
}

}  // namespace

void require_rows(const Trace& trace) {
  if (trace.t_s.empty()) throw TraceError(trace.file + ": the trace has no rows");
}

bool Trace::has(const std::string& name) const { return std::find(names.begin(), names.end(), name) != names.end(); }

const std::vector<double>& Trace::column(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw TraceError(file + ": no column '" + name + "'");
  return columns[static_cast<size_t>(it - names.begin())];
}

std::vector<const std::vector<double>*> Trace::numbered(const std::string& prefix) const {
  std::vector<const std::vector<double>*> out;
  out.push_back(&column(prefix + "0"));
  while (has(prefix + std::to_string(out.size()))) out.push_back(&column(prefix + std::to_string(out.size())));
  return out;
}

Trace read_trace(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw TraceError(path + ": cannot open the trace (a node writes one only when it has trace columns; did it run?)");
  Trace trace;
  trace.file = path;
  std::string line;
  if (!std::getline(in, line)) throw TraceError(path + ": empty file, expected a header 't_s,<columns>'");
  std::vector<std::string> header = split_cells(line);
  if (header.front() != "t_s")
    throw TraceError(path + ":1: the first column must be 't_s', got '" + header.front() + "'");
  trace.names.assign(header.begin() + 1, header.end());
  trace.columns.resize(trace.names.size());
  std::vector<bool> state_column;
  for (const std::string& name : header) state_column.push_back(runtime::is_state_column(name));
  for (int line_no = 2; std::getline(in, line); ++line_no) {
    if (in.eof()) break;  // no newline: an unfinished row (the writer was killed writing it)
    if (line.empty()) continue;
    const std::vector<std::string> cells = split_cells(line);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (cells.size() != header.size()) {
      throw TraceError(where + std::to_string(cells.size()) + " cells, the header has " +
                       std::to_string(header.size()));
    }
    for (size_t i = 0; i < cells.size(); ++i) {
      double value = 0;
      if (state_column[i] ? !parse_state_cell(cells[i], value) : !parse_cell(cells[i], value)) {
        throw TraceError(where + header[i] + ": '" + cells[i] + "' is not a number" +
                         (state_column[i] ? " nor a state's name" : ""));
      }
      if (i == 0) {
        if (!std::isfinite(value)) throw TraceError(where + "t_s: '" + cells[i] + "' is not a time");
        trace.t_s.push_back(value);
      } else {
        trace.columns[i - 1].push_back(value);
      }
    }
  }
  return trace;
}

}  // namespace teleop::experiment
