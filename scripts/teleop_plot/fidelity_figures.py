"""The figures of the fidelity study (experiment/src/fidelity_report.cpp, docs/fidelity.md) from its
trace CSV (sequence, controller, seed, t_s and the error signals) and its segments CSV (the windows
of every pose and movement): per movement, the errors over time of both controllers, as the
coupling thesis's Fig. 4.4 shows them; and the contact sequence's errors over its whole run."""

import math

from figure_style import DPI, HEIGHT_PX, WIDTH_PX, new_figure, pyplot
from study_csv import group_columns, read_rows


class FidelityTraceError(Exception):
    """A trace or segments CSV that cannot be read or lacks the study's columns."""


TRACE_COLUMNS = ("sequence", "controller", "seed", "t_s", "q_rmse_deg", "q_max_joint_deg", "tau_rmse_nm",
                 "tau_max_joint_nm", "ee_position_cm", "ee_rotation")
SEGMENT_COLUMNS = ("sequence", "contact", "controller", "seed", "segment", "kind", "begin_s", "end_s")
COLOURS = {"state_space": "tab:blue", "joint_impedance": "tab:orange"}
LABELS = {"state_space": "state space", "joint_impedance": "joint impedance"}


def read_file(path, required):
    return read_rows(path, required, "fidelity study file", FidelityTraceError)


def read_signals(path):
    """{(sequence, controller, seed): {column: [float]}} in file order."""
    return group_columns(path, read_file(path, TRACE_COLUMNS),
                         lambda row: (row["sequence"], row["controller"], row["seed"]), FidelityTraceError,
                         columns=TRACE_COLUMNS[3:])


def window(columns, key, begin, end):
    """(t relative to begin, values) of `key` inside [begin, end]."""
    pairs = [(t - begin, v) for t, v in zip(columns["t_s"], columns[key]) if begin <= t <= end]
    return [p[0] for p in pairs], [p[1] for p in pairs]


def movement_grid(signals, segments, sequence, seed, key, peak_key, unit, title):
    """One axes per movement of `sequence`: `key` of each controller (solid) and `peak_key` (the
    largest single joint, dashed) over the movement's window."""
    movements = []
    for row in segments:
        if row["sequence"] == sequence and row["seed"] == seed and row["kind"] == "movement":
            if row["segment"] not in [m[0] for m in movements]:
                movements.append((row["segment"], float(row["begin_s"]), float(row["end_s"])))
    columns = 3 if len(movements) > 2 else max(1, len(movements))
    rows = max(1, math.ceil(len(movements) / columns))
    fig, axes = pyplot.subplots(rows, columns, figsize=(WIDTH_PX / DPI, HEIGHT_PX / DPI), dpi=DPI, squeeze=False,
                                layout="constrained")
    fig.suptitle(title, fontsize=13)
    for i, (name, begin, end) in enumerate(movements):
        ax = axes[i // columns][i % columns]
        for controller in COLOURS:
            data = signals.get((sequence, controller, seed))
            if data is None:
                continue
            t, v = window(data, key, begin, end)
            label = f"{LABELS[controller]}: RMSE" if peak_key else LABELS[controller]
            ax.plot(t, v, color=COLOURS[controller], linewidth=1.1, label=label)
            if peak_key:
                t, v = window(data, peak_key, begin, end)
                ax.plot(t, v, color=COLOURS[controller], linewidth=0.8, linestyle="--",
                        label=f"{LABELS[controller]}: largest joint")
        ax.set_title(name, fontsize=10)
        ax.set_ylabel(unit)
        ax.set_xlabel("time in the movement's window [s]")
        ax.grid(True, alpha=0.3)
        ax.set_axisbelow(True)
    for i in range(len(movements), rows * columns):
        axes[i // columns][i % columns].set_visible(False)
    if movements:
        axes[0][0].legend(fontsize=7, loc="upper left")
    return fig


def contact_figure(signals, segments, sequence, seed):
    """The contact sequence's joint, torque and end-effector errors over the whole run, the
    movements shaded."""
    fig, axes = new_figure(3, f"In contact ({sequence}, seed {seed}): real robot against its replay")
    spans = sorted({(float(r["begin_s"]), float(r["end_s"])) for r in segments
                    if r["sequence"] == sequence and r["seed"] == seed and r["kind"] == "movement"})
    for ax, key, unit in zip(axes, ("q_rmse_deg", "tau_rmse_nm", "ee_position_cm"),
                             ("joint RMSE [°]", "torque RMSE [N m]", "end effector [cm]")):
        for begin, end in spans:
            ax.axvspan(begin, end, color="0.92")
        for controller in COLOURS:
            data = signals.get((sequence, controller, seed))
            if data is not None:
                ax.plot(data["t_s"], data[key], color=COLOURS[controller], linewidth=1.0, label=LABELS[controller])
        ax.set_ylabel(unit)
    axes[0].legend(fontsize=8, loc="upper left")
    axes[-1].set_xlabel("time [s]")
    return fig


def fidelity_figures(trace_path, segments_path):
    """[(name, figure)] of the fidelity study's files."""
    signals = read_signals(trace_path)
    segments = read_file(segments_path, SEGMENT_COLUMNS)
    seed = next(iter(signals))[2]
    sequences = []
    for row in segments:
        if (row["sequence"], row["contact"]) not in sequences:
            sequences.append((row["sequence"], row["contact"]))
    figures = []
    for sequence, contact in sequences:
        if not any(key[0] == sequence for key in signals):
            continue
        if contact == "yes":
            figures.append((f"fidelity_{sequence}", contact_figure(signals, segments, sequence, seed)))
            continue
        figures += [
            (f"fidelity_{sequence}_joint_error",
             movement_grid(signals, segments, sequence, seed, "q_rmse_deg", "q_max_joint_deg", "error [°]",
                           f"Joint position error per movement, seed {seed} (thesis Fig. 4.4)")),
            (f"fidelity_{sequence}_torque_error",
             movement_grid(signals, segments, sequence, seed, "tau_rmse_nm", "tau_max_joint_nm", "error [N m]",
                           f"Joint torque error per movement, seed {seed}")),
            (f"fidelity_{sequence}_ee_position_error",
             movement_grid(signals, segments, sequence, seed, "ee_position_cm", None, "error [cm]",
                           f"End-effector position error per movement, seed {seed}")),
            (f"fidelity_{sequence}_ee_rotation_error",
             movement_grid(signals, segments, sequence, seed, "ee_rotation", None, "θ (eq. 4.5)",
                           f"End-effector rotation distance per movement, seed {seed}")),
        ]
    return figures
