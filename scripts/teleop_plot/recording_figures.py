"""The figures of a recording exported as CSV (`teleop bag export`, one `<topic>.csv` per topic,
docs/plots.md): the joint positions of each joint state topic, the force and torque of each
wrench topic, the torques of each joint torque topic, over the time since the recording began."""

import csv
import glob
import os

from figure_style import new_figure

# what a topic's file is drawn as: the column every such topic has, the figure's name and title,
# and its axes as (label, columns of the first message that start with a prefix)
SERIES = [
    ("q_rad[0]", "positions", "joint positions", [("q [rad]", ("q_rad[",))]),
    ("force_n.x", "wrench", "force and torque", [("F [N]", ("force_n.",)), ("τ [N m]", ("torque_nm.",))]),
    ("tau_nm[0]", "torques", "joint torques", [("τ [N m]", ("tau_nm[",))]),
]


class RecordingCsvError(Exception):
    """A folder without exported topics, or a file that cannot be read; the message names it."""


def read_topic(path):
    """{column: [float]} of the numeric columns of one exported topic (text columns left out)."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise RecordingCsvError(f"{path}: {e.strerror}") from e
    columns = {}
    for name in rows[0] if rows else []:
        try:
            columns[name] = [float(row[name]) if row[name] != "" else float("nan") for row in rows]
        except ValueError:
            continue  # names, enums: not drawn
    return columns


def topic_figure(topic, columns, name, title, axes_spec):
    fig, axes = new_figure(len(axes_spec), f"{topic}: {title}")
    for ax, (label, prefixes) in zip(axes, axes_spec):
        for column in (c for c in columns if c.startswith(prefixes)):
            ax.plot(columns["t_s"], columns[column], linewidth=1.0, label=column)
        ax.set_ylabel(label)
        ax.legend(loc="best", fontsize=8, ncol=2)
    axes[-1].set_xlabel("time since the recording began [s]")
    return topic.replace("/", ".") + "_" + name, fig


def recording_figures(csv_dir):
    """[(file name, figure)] of every exported topic in `csv_dir` that SERIES draws."""
    paths = sorted(glob.glob(os.path.join(csv_dir, "*.csv")))
    if not paths:
        raise RecordingCsvError(f"{csv_dir}: no exported topic (*.csv) here (teleop bag export writes them)")
    figures = []
    for path in paths:
        topic = os.path.splitext(os.path.basename(path))[0].replace(".", "/")
        columns = read_topic(path)
        if "t_s" not in columns:
            continue
        for marker, name, title, axes_spec in SERIES:
            if marker in columns:
                figures.append(topic_figure(topic, columns, name, title, axes_spec))
    return figures
