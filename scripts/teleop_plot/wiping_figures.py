"""The wiping study's figure (experiment/src/wiping_report.cpp, docs/fidelity.md) from its wipes CSV
(one row per sweep cell and wipe): per wiper x-angle, the peak external torque of every joint over
the wipes, one bar per panel height (the coupling thesis's Table 4.4 drawn), with the real robot's
first-contact peaks of joints 0 and 3 that the thesis reports."""

import csv

from figure_style import new_figure

TORQUE_COLUMNS = [f"tau_ext_peak_j{j}_nm" for j in range(7)]
REQUIRED = ("wiper_angle_rad", "panel_height_m", "wipe", "contact") + tuple(TORQUE_COLUMNS)
THESIS_REAL_PEAKS_NM = {0: 14.0, 3: 8.0}  # §4.4.2, the first contact


class WipingCsvError(Exception):
    """A wipes CSV that cannot be read or lacks the study's columns."""


def read_cells(path):
    """{(angle, height): {"contacts": n, "wipes": n, "peaks": [7 floats]}} in file order."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.DictReader(f)
            missing = [c for c in REQUIRED if c not in (reader.fieldnames or [])]
            if missing:
                raise WipingCsvError(f"{path}: not a wiping study file (no {', '.join(missing)} column)")
            rows = list(reader)
    except OSError as e:
        raise WipingCsvError(f"{path}: {e.strerror}") from e
    if not rows:
        raise WipingCsvError(f"{path}: no wipes")
    cells = {}
    for row in rows:
        cell = cells.setdefault((float(row["wiper_angle_rad"]), float(row["panel_height_m"])),
                                {"contacts": 0, "wipes": 0, "peaks": [0.0] * 7})
        cell["wipes"] += 1
        cell["contacts"] += int(row["contact"])
        if int(row["contact"]):
            cell["peaks"] = [max(p, float(row[c])) for p, c in zip(cell["peaks"], TORQUE_COLUMNS)]
    return cells


def wiping_figures(path):
    """[(name, figure)]: the torque peaks per sweep cell."""
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
    return [("wiping_torque_peaks", fig)]
