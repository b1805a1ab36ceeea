"""The wiping study's figures (experiment/src/wiping_report.cpp, docs/fidelity.md): from its wipes
CSV (one row per sweep cell and wipe), per wiper x-angle the peak external torque of every joint
over the wipes, one bar per panel height (the coupling thesis's Table 4.4 drawn), with the real
robot's first-contact peaks of joints 0 and 3 that the thesis reports; from its trace CSV, joints 0
and 3's estimated external torque over time in every cell (the thesis's Fig. 4.13) and the hand's
height (its Fig. 4.15)."""

from figure_style import new_figure, pyplot
from study_csv import group_columns, read_rows

TORQUE_COLUMNS = [f"tau_ext_peak_j{j}_nm" for j in range(7)]
REQUIRED = ("wiper_angle_rad", "panel_height_m", "wipe", "contact") + tuple(TORQUE_COLUMNS)
THESIS_REAL_PEAKS_NM = {0: 14.0, 3: 8.0}  # §4.4.2, the first contact


class WipingCsvError(Exception):
    """A wipes CSV that cannot be read or lacks the study's columns."""


def read_cells(path):
    """{(angle, height): {"contacts": n, "wipes": n, "peaks": [7 floats]}} in file order."""
    rows = read_rows(path, REQUIRED, "wiping study file", WipingCsvError)
    if not rows:
        raise WipingCsvError(f"{path}: no wipes")
    cells = {}
    try:
        for row in rows:
            cell = cells.setdefault((float(row["wiper_angle_rad"]), float(row["panel_height_m"])),
                                    {"contacts": 0, "wipes": 0, "peaks": [0.0] * 7})
            cell["wipes"] += 1
            cell["contacts"] += int(row["contact"])
            if int(row["contact"]):
                cell["peaks"] = [max(p, float(row[c])) for p, c in zip(cell["peaks"], TORQUE_COLUMNS)]
    except ValueError as e:
        raise WipingCsvError(f"{path}: {e}") from e
    return cells


TRACE_COLUMNS = ("wiper_angle_rad", "panel_height_m", "t_s", "tau_ext_j0_nm", "tau_ext_j3_nm", "hand_z_m")


def read_trace(path):
    """{(angle, height): {column: [float]}} in file order."""
    return group_columns(path, read_rows(path, TRACE_COLUMNS, "wiping trace", WipingCsvError),
                         lambda row: (float(row["wiper_angle_rad"]), float(row["panel_height_m"])), WipingCsvError,
                         columns=TRACE_COLUMNS[2:])


def torques_over_time(trace):
    """Per wiper angle, J0 (solid) and J3 (dashed) of every panel height over the run."""
    angles = sorted({a for a, _ in trace}, reverse=True)
    heights = sorted({h for _, h in trace})
    colours = pyplot.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, axes = new_figure(len(angles), "Wiping study: estimated external torque over time, J0 solid, J3 dashed "
                           "(thesis Fig. 4.13)")
    for ax, angle in zip(axes, angles):
        for k, height in enumerate(heights):
            columns = trace.get((angle, height))
            if columns is None:
                continue
            colour = colours[k % len(colours)]
            ax.plot(columns["t_s"], columns["tau_ext_j0_nm"], color=colour, linewidth=1, label=f"panel {height:.3f} m")
            ax.plot(columns["t_s"], columns["tau_ext_j3_nm"], color=colour, linewidth=1, linestyle="--")
        ax.set_ylabel("tau_ext [N m]")
        ax.set_title(f"wiper x-angle {angle:g} rad", fontsize=10)
        ax.legend(fontsize=8, loc="upper right")
    axes[-1].set_xlabel("t [s]")
    return fig


def hand_height(trace):
    """The hand's height over time for every cell of the first (largest) angle (thesis Fig. 4.15)."""
    angle = max(a for a, _ in trace)
    fig, axes = new_figure(1, f"Wiping study: the hand's height, wiper x-angle {angle:g} rad (thesis Fig. 4.15)")
    for height in sorted({h for a, h in trace if a == angle}):
        columns = trace[(angle, height)]
        axes[0].plot(columns["t_s"], columns["hand_z_m"], linewidth=1, label=f"panel {height:.3f} m")
    axes[0].set_ylabel("hand z [m]")
    axes[0].set_xlabel("t [s]")
    axes[0].legend(fontsize=8)
    return fig


def wiping_figures(path, trace_path):
    """[(name, figure)]: the torque peaks per sweep cell, the torques over time, the hand's height."""
    trace = read_trace(trace_path)
    figures = [("wiping_torques_over_time", torques_over_time(trace)), ("wiping_hand_height", hand_height(trace))]
    return [("wiping_torque_peaks", torque_peaks(path))] + figures


def torque_peaks(path):
    """The per-joint peaks of every sweep cell, a row per angle."""
    cells = read_cells(path)
    angles = sorted({a for a, _ in cells}, reverse=True)
    heights = sorted({h for _, h in cells})
    fig, axes = new_figure(len(angles), "Wiping study: peak external torque per joint and sweep cell "
                           "(momentum observer; thesis Table 4.4)")
    width = 0.8 / len(heights)
    # one scale for every row: the angles compare at a glance
    top = 1.1 * max([max(c["peaks"]) for c in cells.values()] + list(THESIS_REAL_PEAKS_NM.values()))
    for ax, angle in zip(axes, angles):
        for k, height in enumerate(heights):
            cell = cells.get((angle, height))
            if cell is None:
                continue
            xs = [j + (k - (len(heights) - 1) / 2) * width for j in range(7)]
            label = f"panel {height:.3f} m: {cell['contacts']}/{cell['wipes']} contacts"
            ax.bar(xs, cell["peaks"], width, label=label)
        for joint, peak in THESIS_REAL_PEAKS_NM.items():
            ax.plot([joint - 0.45, joint + 0.45], [peak, peak], "k--", linewidth=1)
        ax.set_ylim(0, top)
        ax.set_ylabel("|tau_ext| peak [N m]")
        ax.set_title(f"wiper x-angle {angle:g} rad (dashed: Justin's real peaks, J0 and J3, first contact)",
                     fontsize=10)
        ax.legend(fontsize=8, loc="upper right")
    axes[-1].set_xticks(range(7))
    axes[-1].set_xticklabels([f"J{j}" for j in range(7)])
    axes[-1].set_xlabel("joint (zero-indexed, as in the thesis)")
    return fig
