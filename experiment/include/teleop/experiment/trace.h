#pragma once
// A node's time trace as written by runtime::TraceRecorder (`t_s,wall_s,lateness_us,<columns>`
// CSV; older traces have `t_s,<columns>`), read back for the analysis.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace teleop::experiment {

/// A trace file that is missing, malformed or lacks a column. The message names the file (and
/// the line or column).
class TraceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Columns of one trace, each as long as `t_s`.
struct Trace {
  std::string file;
  std::vector<double> t_s;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;

  bool has(const std::string& name) const;
  /// The column called `name`; throws TraceError naming the file and the column when absent.
  const std::vector<double>& column(const std::string& name) const;
  /// The columns `<prefix>0`, `<prefix>1`, ... as long as they exist (e.g. q_0 .. q_6); throws
  /// TraceError when there is not even `<prefix>0`.
  std::vector<const std::vector<double>*> numbered(const std::string& prefix) const;
};

/// Throws TraceError naming the file when `trace` has no rows.
void require_rows(const Trace& trace);

/// Reads a trace CSV. Empty cells and `nan` read as NaN; a state column (runtime::is_state_column)
/// reads a state's name (`running`) or number as the msg::NodeState's number. Throws TraceError
/// when the file cannot be read, has no `t_s` first column, or a row with the wrong number of
/// cells or a bad number. A last line without its newline is a row its writer did not finish (a
/// node SIGKILLed mid-write, `--trace-stream`): it is not read, every finished row is.
Trace read_trace(const std::string& path);

}  // namespace teleop::experiment
