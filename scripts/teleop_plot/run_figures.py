"""The figures of one run (docs/plots.md). Each takes a run_traces.Run and returns its figures as
[(file name, figure)], or raises Skip naming the columns the run lacks."""

import numpy
from matplotlib.ticker import FuncFormatter

from figure_style import new_figure
from run_traces import STATE_NAMES

AXES = ("x", "y", "z")
# one colour per role, the same in every figure
LEADER, FOLLOWER, ESTIMATE = "tab:blue", "tab:orange", "tab:green"
# the force figure's series: column prefix, colour, line style, what it is
FORCES = [("f_felt_", LEADER, "-", "felt"), ("f_ext_", FOLLOWER, "--", "exerted"),
          ("f_est_", ESTIMATE, ":", "estimated")]


class Skip(Exception):
    """The run lacks what a figure shows; the message says what."""


def arm_prefixes(run, column):
    """The prefixes p of the columns p + `column` in the run's traces: "" for a node of one arm,
    "left_", "right_" for an arm of a group (runtime::ArmGroup), in order of appearance."""
    prefixes = []
    for trace in run.traces:
        for name in trace.names:
            if name.endswith(column) and name[: -len(column)] not in prefixes:
                prefixes.append(name[: -len(column)])
    return prefixes


def arm_of(column, name):
    """`column`'s arm ("left") when it is `name` prefixed by one, else ""."""
    return column[: -len(name)].rstrip("_")


def colour_of(trace):
    """The leader's colour for a trace that commands (x_cmd_*), the follower's for the others."""
    return LEADER if any(n.endswith("x_cmd_x") for n in trace.names) else FOLLOWER


def titled(title, run, prefix=""):
    arm = f" ({prefix.rstrip('_')} arm)" if prefix else ""
    return f"{title}{arm} — {run.title}"


def norm(trace, prefix):
    return numpy.sqrt(sum(trace[prefix + a] ** 2 for a in AXES))


def time_axis(run, axes):
    """The time label, and on every axes the run's marks: the operator's start and the analysis'
    windows (an experiment's hold window), when the run has them."""
    axes[-1].set_xlabel(run.time_label())
    if run.origin_s is None:
        return
    for ax in axes:
        ax.axvline(run.origin_s, color="grey", linestyle=":", linewidth=1.0)
        for label, (begin, end) in run.windows:
            ax.axvspan(run.origin_s + begin, run.origin_s + end, color="grey", alpha=0.12, linewidth=0)
    top = axes[0]
    top.annotate("operator begins", (run.origin_s, 1.0), xycoords=("data", "axes fraction"), fontsize=7,
                 color="grey", va="bottom")
    for label, (begin, _) in run.windows:
        top.annotate(label, (run.origin_s + begin, 1.0), xycoords=("data", "axes fraction"), fontsize=7,
                     color="grey", va="bottom")


def finish(run, axes):
    axes[0].legend(loc="best", fontsize=9)
    time_axis(run, axes)


def position(run):
    """Commanded (leader x_cmd_*) vs actual (follower x_*) flange position, per axis."""
    figures = []
    for p in arm_prefixes(run, "x_cmd_x"):
        commanded, actual = run.with_column(p + "x_cmd_x"), run.with_column(p + "x_x")
        if not actual:
            continue
        fig, axes = new_figure(3, titled("Flange position: commanded vs actual", run, p))
        for ax, a in zip(axes, AXES):
            for t in commanded:
                ax.plot(run.time(t), t[p + "x_cmd_" + a], color=LEADER, label=f"commanded ({t.node} x_cmd)")
            for t in actual:
                ax.plot(run.time(t), t[p + "x_" + a], color=FOLLOWER, linestyle="--", label=f"actual ({t.node} x)")
            ax.set_ylabel(f"{a} [m]")
        finish(run, axes)
        figures.append((p + "position", fig))
    if not figures:
        raise Skip("no commanded (x_cmd_x/y/z) together with actual (x_x/y/z) flange position")
    return figures


def force(run):
    """Force the operator feels (leader f_felt_*) vs the force the follower exerts (f_ext_*, the
    simulation's ground truth) and estimates (f_est_*), per axis and as a norm."""
    figures = []
    for p in arm_prefixes(run, "f_felt_x"):
        series = [(t, p + column, colour, style, f"{what} ({t.node} {column.rstrip('_')})")
                  for column, colour, style, what in FORCES for t in run.with_column(p + column + "x")]
        if all(column == p + "f_felt_" for _, column, _, _, _ in series):
            continue
        fig, axes = new_figure(4, titled("Force: felt by the operator vs exerted by the follower", run, p))
        for ax, a in zip(axes, AXES + ("norm",)):
            for t, column, colour, style, label in series:
                value = norm(t, column) if a == "norm" else t[column + a]
                ax.plot(run.time(t), value, color=colour, linestyle=style, label=label)
            ax.set_ylabel("|f| [N]" if a == "norm" else f"f_{a} [N]")
        finish(run, axes)
        figures.append((p + "force", fig))
    if not figures:
        raise Skip("no force felt (f_felt_x/y/z) together with a force exerted (f_ext_x/y/z) or "
                   "estimated (f_est_x/y/z)")
    return figures


def tdpa_energy(run):
    """The TDPA passivity observers' energy on both sides (>= 0: passive)."""
    lines = [(t, c) for p in arm_prefixes(run, "tdpa_w_j") for t in run.with_column(p + "tdpa_w_j")
             for c in [p + "tdpa_w_j"] if numpy.isfinite(t[c]).any()]
    if not lines:
        raise Skip("no TDPA energy (tdpa_w_j absent or all NaN: an architecture without TDPA)")
    # one axes per side: each on its own scale (the two sides' energies differ by orders of magnitude)
    fig, axes = new_figure(len(lines), titled("TDPA: observed energy (>= 0: passive) and what the controller dissipated",
                                              run))
    for ax, (t, c) in zip(axes, lines):
        time = run.time(t)
        ax.plot(time, t[c], color=colour_of(t), label=f"{t.node} {c} (observed)")
        ax.axhline(0.0, color="black", linewidth=0.8)
        prefix = c[:-len("tdpa_w_j")]
        # traces since issue 34: the energy the controller took out so far, and when it acted
        if t.has(prefix + "tdpa_dissipated_j") and numpy.isfinite(t[prefix + "tdpa_dissipated_j"]).any():
            ax.plot(time, t[prefix + "tdpa_dissipated_j"], color="black", linestyle="--", linewidth=1.0,
                    label=f"{t.node} dissipated by its controller")
        if t.has(prefix + "tdpa_acting"):
            ax.fill_between(time, 0, 1, where=t[prefix + "tdpa_acting"] > 0.5, transform=ax.get_xaxis_transform(),
                            color="red", alpha=0.15, linewidth=0, label="controller acting")
        arm = arm_of(c, "tdpa_w_j")
        ax.set_ylabel(f"{t.node} {arm} [J]" if arm else f"{t.node} [J]")
        ax.legend(loc="upper right", fontsize=9)
    time_axis(run, axes)
    return [("tdpa_energy", fig)]


def lateness(run):
    """Every node's wake-up lateness after its cycle's deadline."""
    traces = run.with_column("lateness_us")
    if not traces:
        raise Skip("no lateness_us column (traces written before it had one)")
    fig, axes = new_figure(len(traces), titled("Loop lateness: wake-up after the cycle's deadline", run))
    for ax, t in zip(axes, traces):
        late = t["lateness_us"]
        p50, p99 = numpy.nanpercentile(late, [50, 99])
        label = f"{t.node}: p50 {p50:.1f} µs, p99 {p99:.1f} µs, max {numpy.nanmax(late):.0f} µs"
        ax.plot(run.time(t), late, color=colour_of(t), linewidth=0.8, label=label)
        # linear up to 10 µs (the usual wake-up), logarithmic above (the stalls); plain numbers
        ax.set_yscale("symlog", linthresh=10.0)
        ax.set_ylim(0.0, max(20.0, 2.0 * numpy.nanmax(late)))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        ax.set_ylabel(f"{t.node} [µs]")
        ax.legend(loc="upper right", fontsize=9)
    time_axis(run, axes)
    return [("lateness", fig)]


def states(run):
    """Every node's state (each arm's in a node of several) over time."""
    rows = [(t, c) for t in run.traces for c in t.state_columns()]
    if not rows:
        raise Skip("no state column")
    fig, axes = new_figure(len(rows), titled("Node states", run))
    for ax, (t, c) in zip(axes, rows):
        ax.step(run.time(t), t[c], where="post", color=colour_of(t))
        ax.set_yticks(range(len(STATE_NAMES)), STATE_NAMES, fontsize=8)
        ax.set_ylim(-0.5, len(STATE_NAMES) - 0.5)
        arm = arm_of(c, "state")
        ax.set_ylabel(f"{t.node}\n{arm}" if arm else t.node)
    time_axis(run, axes)
    return [("states", fig)]


FIGURES = [("position", position), ("force", force), ("tdpa_energy", tdpa_energy), ("lateness", lateness),
           ("states", states)]
