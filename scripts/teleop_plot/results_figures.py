"""The figures of an experiment's results CSV (experiment/src/results_table.cpp): one per numeric
metric, grouped bars comparing the runs (x axis) under each network profile (one bar each)."""

import csv

from figure_style import new_figure

# columns that name or explain a row; every other column whose cells are numbers is a metric
NOT_METRICS = {"run", "profile", "repeat", "seed", "status", "stable", "stable_why", "trace_dir", "note"}
# the unit a metric's name ends in (docs/experiments.md: SI units in the names)
UNITS = [("_fraction", "fraction of cycles"), ("_mm", "mm"), ("_rad", "rad"), ("_n", "N"), ("_m", "m"), ("_j", "J"),
         ("_s", "s")]


class ResultsError(Exception):
    """A results CSV that cannot be read or has no metric."""


def number(cell):
    try:
        return float(cell)
    except ValueError:
        return None


def unit_of(metric):
    return next((unit for suffix, unit in UNITS if metric.endswith(suffix)), "")


def read_results(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise ResultsError(f"{path}: {e.strerror}") from e
    if not rows or "run" not in rows[0] or "profile" not in rows[0]:
        raise ResultsError(f"{path}: not an experiment's results (no rows, or no run and profile columns)")
    return rows


def metrics_of(rows):
    """The numeric columns: every cell a number or empty (no sample), at least one a number; the
    yes/no flags are not."""
    names = [n for n in rows[0] if n not in NOT_METRICS]
    return [n for n in names if all(r[n] == "" or number(r[n]) is not None for r in rows)
            and any(r[n] != "" for r in rows)]


def unique(values):
    return list(dict.fromkeys(values))


def cell_values(rows, metric):
    """{(run, profile): [values of the ok repeats]} and {(run, profile): status to show instead}: a
    cell none of whose repeats is ok (failed, or invalid: its numbers are no result) shows the
    status of its first repeat, not a bar."""
    values, shown = {}, {}
    for r in rows:
        key = (r["run"], r["profile"])
        status = r.get("status", "ok") or "ok"
        if status == "ok" and r[metric] != "":
            values.setdefault(key, []).append(number(r[metric]))
        elif status != "ok":
            shown.setdefault(key, status)
    return values, {k: v for k, v in shown.items() if k not in values}


def mean_and_sd(values):
    mean = sum(values) / len(values)
    if len(values) < 2:
        return mean, None
    return mean, (sum((v - mean) ** 2 for v in values) / (len(values) - 1)) ** 0.5


def draw_limit(ax, limit, tops):
    """The verdict's limit as a dashed line; one far above every bar (a quiet run's MAD is a
    thousandth of its limit) is said in a corner instead, so that the bars stay visible."""
    top = max(tops, default=0.0)
    if top > 0 and limit > 2 * top:
        ax.text(0.01, 0.98, f"stable at or below {limit:g} (above every bar)", transform=ax.transAxes, color="red",
                fontsize=8, va="top")
        return
    ax.axhline(limit, color="red", linestyle="--", linewidth=1.0, label=f"stable at or below {limit:g}")


def metric_figure(rows, metric, title, limit=None):
    """Grouped bars: the mean over a cell's ok repeats, an error bar of one sample standard
    deviation where there are two or more."""
    runs, profiles = unique(r["run"] for r in rows), unique(r["profile"] for r in rows)
    values, shown = cell_values(rows, metric)
    fig, axes = new_figure(1, f"{metric} by run and network profile — {title}", sharex=False)
    ax = axes[0]
    width = 0.8 / len(profiles)
    for k, profile in enumerate(profiles):
        xs = [i + (k - (len(profiles) - 1) / 2) * width for i in range(len(runs))]
        stats = [mean_and_sd(values[(run, profile)]) if (run, profile) in values else (0.0, None) for run in runs]
        errors = [sd or 0.0 for _, sd in stats]
        bars = ax.bar(xs, [m for m, _ in stats], width, label=profile,
                      yerr=errors if any(errors) else None, capsize=3 if any(errors) else 0)
        # each bar says its number (± its spread); a cell without a sample says why instead of a 0
        labels = [(f"{m:.3g}" if sd is None else f"{m:.3g}±{sd:.2g}") if (run, profile) in values
                  else shown.get((run, profile), "n/a") for run, (m, sd) in zip(runs, stats)]
        ax.bar_label(bars, labels, fontsize=8, padding=2)
    ax.axhline(0.0, color="black", linewidth=0.8)
    if limit is not None:
        draw_limit(ax, limit, [m + (sd or 0.0) for vs in values.values() for m, sd in [mean_and_sd(vs)]])
    ax.set_xticks(range(len(runs)), runs)
    # a group is 0.8 wide: a run alone does not fill the axes; room above the bars for their numbers
    ax.set_xlim(-1.0, len(runs))
    ax.margins(y=0.1)
    ax.set_xlabel("run")
    unit = unit_of(metric)
    ax.set_ylabel(f"{metric} [{unit}]" if unit else metric)
    ax.legend(title="network profile", fontsize=9, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return fig


def results_figures(path, title, limits=None):
    """[(metric, figure)] of the results CSV at `path`; `limits`: {metric: the stability
    verdict's limit}, drawn on that metric's figure."""
    limits = limits or {}
    rows = read_results(path)
    metrics = metrics_of(rows)
    if not metrics:
        raise ResultsError(f"{path}: no metric column with a number")
    return [(metric, metric_figure(rows, metric, title, limits.get(metric))) for metric in metrics]
