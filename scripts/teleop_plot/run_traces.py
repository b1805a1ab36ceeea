"""The traces of one run: `<node>.csv` files as runtime::TraceRecorder writes them.

Header `t_s,wall_s,lateness_us,<columns>` (older traces: `t_s,<columns>`); a state column (`state`,
`<arm>_state`) holds a node state's name (older traces: its number).
"""

import glob
import os
import warnings

import numpy

# msg::NodeState in the IDL's order (idl/status.idl), named as runtime/status_names.cpp names them
STATE_NAMES = ["starting", "running", "safe_hold", "fault", "stopping"]


class TraceError(Exception):
    """A run dir without traces, or a trace that cannot be read; the message names the file."""


def is_state_column(name):
    """The trace's convention for a state column (runtime::is_state_column)."""
    return name == "state" or (name.endswith("_state") and len(name) > len("_state"))


def _state_value(cell):
    text = cell.decode() if isinstance(cell, bytes) else cell
    text = text.strip()
    if text in STATE_NAMES:
        return float(STATE_NAMES.index(text))
    return float(text)  # an older trace's number, or nan


class Trace:
    """One node's trace: its name (the file's stem), columns by name as float arrays."""

    def __init__(self, path):
        self.path = path
        self.node = os.path.splitext(os.path.basename(path))[0]
        with open(path, encoding="utf-8") as f:
            self.names = f.readline().strip().split(",")
        if not self.names or self.names[0] != "t_s":
            raise TraceError(f"{path}: not a trace (its first column is not t_s)")
        converters = {i: _state_value for i, n in enumerate(self.names) if is_state_column(n)}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)  # "input contained no data": a header alone
                data = numpy.loadtxt(path, delimiter=",", skiprows=1, ndmin=2, converters=converters,
                                     encoding="utf-8")
        except ValueError as e:
            raise TraceError(f"{path}: {e}") from e
        self.columns = {n: data[:, i] for i, n in enumerate(self.names)} if data.size else {}

    def rows(self):
        return len(self.columns.get("t_s", []))

    def has(self, name):
        return name in self.columns

    def __getitem__(self, name):
        return self.columns[name]

    def state_columns(self):
        return [n for n in self.names if is_state_column(n)]


def is_trace_file(path):
    """A CSV whose header starts with t_s (a run dir may hold other CSVs)."""
    try:
        with open(path, encoding="utf-8") as f:
            return f.readline().startswith("t_s,")
    except (OSError, UnicodeDecodeError):
        return False


class Run:
    """The traces of a run dir that have rows, and the time axis they share."""

    def __init__(self, run_dir):
        if not os.path.isdir(run_dir):
            raise TraceError(f"{run_dir}: no such directory")
        files = sorted(p for p in glob.glob(os.path.join(run_dir, "*.csv")) if is_trace_file(p))
        if not files:
            raise TraceError(f"{run_dir}: no trace in this directory (expected <node>.csv files with a t_s column, "
                             "as `teleop launch --trace-dir` or `teleop experiment` write them)")
        self.dir = run_dir
        # <run>/<profile> of an experiment's run dir, <run>/<profile>/r<k> of a repeat
        parts = os.path.abspath(run_dir).split(os.sep)
        repeat = len(parts) >= 3 and parts[-1][:1] == "r" and parts[-1][1:].isdigit()
        self.title = " / ".join(parts[-3:] if repeat else parts[-2:])
        self.traces = [t for t in (Trace(p) for p in files) if t.rows() > 0]
        if not self.traces:
            raise TraceError(f"{run_dir}: every trace is empty (a header, no rows)")
        # the wall clock lines up nodes of several hosts; traces without it share the monotonic one
        self.clock = "wall_s" if all(t.has("wall_s") for t in self.traces) else "t_s"
        self.start_s = min(t[self.clock][0] for t in self.traces)
        # set by mark(): when the operator began [s on time()], and windows [s after it]
        self.origin_s = None
        self.windows = []

    def mark(self, leader, windows):
        """Marks the operator's start, read from the trace of node `leader` (its first
        `operator_s` column: the first row where that clock runs, less its value; without one its
        first row), and `windows` [(label, (begin, end))] in seconds after it. Returns the start,
        or None when no trace is the leader's."""
        trace = next((t for t in self.traces if t.node == leader), None)
        if trace is None:
            return None
        time = self.time(trace)
        self.origin_s = float(time[0])
        clock = next((n for n in trace.names if n.endswith("operator_s")), None)
        if clock is not None:
            running = numpy.nonzero(trace[clock] > 0)[0]
            if len(running) > 0:
                self.origin_s = float(time[running[0]] - trace[clock][running[0]])
        self.windows = windows
        return self.origin_s

    def time(self, trace):
        """Seconds since the run's first row, on the clock every trace has."""
        return trace[self.clock] - self.start_s

    def time_label(self):
        clock = "wall clock" if self.clock == "wall_s" else "monotonic clock"
        return f"time since the run's first row [s] ({clock})"

    def with_column(self, name):
        return [t for t in self.traces if t.has(name)]
