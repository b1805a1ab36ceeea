"""The figures of the SVH hand study (experiment/src/hand_study_report.cpp, docs/hand.md) from its
trace CSV (run, t_s, recording, tip_force_n, one column per joint): the index tip's force over time
per run (the paper's Fig. 4), and two joints over time (its Figs. 5 and 6)."""

import math

from figure_style import DPI, HEIGHT_PX, WIDTH_PX, pyplot
from study_csv import group_columns, read_rows


class HandTraceError(Exception):
    """A trace CSV that cannot be read or lacks the study's columns."""


REQUIRED = ("run", "t_s", "recording", "tip_force_n", "shoulder_pan_joint", "Index_Finger_Proximal")


def read_runs(path):
    """{run: {column: [float]}} in file order."""
    rows = read_rows(path, REQUIRED, "hand study trace", HandTraceError)
    return group_columns(path, rows, lambda row: row["run"], HandTraceError, skip=("run",))


def recording_start(columns):
    """The time the recording window begins (the first sample flagged as recorded)."""
    return next((t for t, rec in zip(columns["t_s"], columns["recording"]) if rec), columns["t_s"][-1])


def tip_force_figure(runs):
    """One axes per run, in a grid of two columns (the study lists its constraint runs, then its
    servo runs): the normal force at the index tip, the recording window shaded."""
    names = list(runs)
    rows = math.ceil(len(names) / 2)
    columns = 2 if len(names) > 1 else 1
    fig, axes = pyplot.subplots(rows, columns, figsize=(WIDTH_PX / DPI, HEIGHT_PX / DPI), dpi=DPI, sharex=True,
                                squeeze=False, layout="constrained")
    fig.suptitle("Index tip contact force (touch sensor) — the paper's Fig. 4", fontsize=13)
    for i, name in enumerate(names):
        ax = axes[i % rows][i // rows]
        data = runs[name]
        ax.axvspan(recording_start(data), data["t_s"][-1], color="0.9", label="recording")
        ax.plot(data["t_s"], data["tip_force_n"], color="tab:orange", linewidth=1.2)
        ax.set_title(name, fontsize=10)
        ax.set_ylabel("N")
        ax.grid(True, alpha=0.3)
        ax.set_axisbelow(True)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    for i in range(len(names), rows * columns):
        axes[i % rows][i // rows].set_visible(False)
    return fig


def joints_figure(runs):
    """shoulder_pan_joint and Index_Finger_Proximal over time, every run (the paper's Figs. 5, 6)."""
    fig, axes = pyplot.subplots(2, 1, figsize=(WIDTH_PX / DPI, HEIGHT_PX / DPI), dpi=DPI, sharex=True,
                                squeeze=False, layout="constrained")
    fig.suptitle("Joint positions — the paper's Figs. 5 and 6", fontsize=13)
    for ax, joint in zip(axes[:, 0], ("shoulder_pan_joint", "Index_Finger_Proximal")):
        for name, data in runs.items():
            ax.plot(data["t_s"], data[joint], linewidth=1.0, label=name)
        ax.set_ylabel(f"{joint} [rad]")
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    axes[-1, 0].set_xlabel("time [s]")
    return fig


def hand_figures(path):
    """[(name, figure)] of the hand study trace at `path`."""
    runs = read_runs(path)
    return [("hand_tip_force", tip_force_figure(runs)), ("hand_joints", joints_figure(runs))]
