"""The figures of the PARTI studies (docs/fidelity.md) from their trace CSVs:
"margins" (experiment/src/safety_margin_report.cpp): the distances over time per case, beside the
paper's Fig. 5 (its twin's collision meshes stay >= 0);
"twin" (experiment/src/parti_twin_report.cpp): the real robot against its replay in the nominal
twin, the end-effector pose and contact-wrench error norms over time (the paper's Fig. 7), and the
estimators' contact force against the true one (Fig. 6's right column)."""

from figure_style import new_figure
from study_csv import group_columns, read_rows


class PartiTraceError(Exception):
    """A trace CSV that cannot be read or lacks the study's columns."""


MARGIN_COLUMNS = ("case", "activation_m", "t_s", "twin_margin_m", "physical_margin_m", "arms_m")
TWIN_COLUMNS = ("seed", "t_s", "contact", "ee_position_mm", "ee_rotation_mrad", "force_error_n", "moment_error_nm",
                "f_true_z_n", "f_twin_z_n")
TEXT_COLUMNS = ("case", "phase")  # labels, not numbers
ESTIMATORS = (("observer", "momentum observer (eqs. 6-8)", "tab:green"),
              ("parti_link", "PARTI eq. 5, τd = 0: g − τJ", "tab:red"),
              ("parti_command", "PARTI eq. 5, τd = eq. 4 command", "tab:purple"),
              ("direct_inertial", "direct with M q̈ + n", "tab:grey"))


def read(path, required, key):
    rows = read_rows(path, required, "PARTI study trace", PartiTraceError)
    return group_columns(path, rows, lambda row: row[key], PartiTraceError, skip=(key,) + TEXT_COLUMNS)


def margin_figure(path):
    runs = read(path, MARGIN_COLUMNS, "case")
    fig, axes = new_figure(3, "Two hands driven into each other (PARTI Fig. 5: distance ≥ 0)")
    keys = (("twin_margin_m", "twin's margin spheres [mm]"), ("physical_margin_m", "spheres on the operated arm [mm]"),
            ("arms_m", "arms' own geometry [mm]"))
    for ax, (key, unit) in zip(axes, keys):
        ax.axhline(0.0, color="black", linewidth=0.8)
        for name, data in runs.items():
            activation = 1000 * data["activation_m"][0]
            ax.plot(data["t_s"], [1000 * v for v in data[key]], linewidth=1.1,
                    label=f"{name} (activation {activation:g} mm)")
        ax.set_ylabel(unit)
    axes[0].legend(fontsize=8, loc="upper right")
    axes[-1].set_xlabel("time [s]")
    return fig


def shade_contact(ax, data):
    """Grey spans where the real robot touched the table (the paper's grey bars)."""
    start = None
    for t, c in zip(data["t_s"], data["contact"]):
        if c and start is None:
            start = t
        elif not c and start is not None:
            ax.axvspan(start, t, color="0.9")
            start = None
    if start is not None:
        ax.axvspan(start, data["t_s"][-1], color="0.9")


def twin_error_figure(runs):
    fig, axes = new_figure(4, "Real robot against its replay in the twin: error norms (PARTI Fig. 7)")
    keys = (("ee_position_mm", "position [mm]"), ("ee_rotation_mrad", "rotation [mrad]"),
            ("force_error_n", "contact force [N]"), ("moment_error_nm", "contact moment [N m]"))
    first = next(iter(runs.values()))
    for ax, (key, unit) in zip(axes, keys):
        shade_contact(ax, first)
        for seed, data in runs.items():
            ax.plot(data["t_s"], data[key], linewidth=0.9, label=f"seed {seed}")
        ax.set_ylabel(unit)
    axes[0].legend(fontsize=8, loc="upper left")
    axes[-1].set_xlabel("time [s]")
    return fig


def estimator_figure(runs):
    seed, data = next(iter(runs.items()))
    fig, axes = new_figure(2, f"External force at the end effector, seed {seed} (PARTI Fig. 6, right)")
    for ax in axes:
        shade_contact(ax, data)
    axes[0].plot(data["t_s"], data["f_true_z_n"], color="black", linewidth=1.4, label="true (contacts), real robot")
    axes[0].plot(data["t_s"], data["f_twin_z_n"], color="tab:blue", linewidth=1.0, linestyle="--",
                 label="true (contacts), twin")
    for name, label, colour in ESTIMATORS:
        if f"f_{name}_z_n" in data:
            axes[0].plot(data["t_s"], data[f"f_{name}_z_n"], color=colour, linewidth=0.9, label=label)
            axes[1].plot(data["t_s"], data[f"err_{name}_n"], color=colour, linewidth=0.9, label=label)
    axes[0].set_ylabel("F_z [N]")
    axes[1].set_ylabel("|F_est − F_true| [N]")
    axes[1].set_yscale("symlog", linthresh=1.0)
    axes[0].legend(fontsize=7, loc="upper left")
    axes[-1].set_xlabel("time [s]")
    return fig


def parti_figures(kind, path):
    """[(name, figure)] of a PARTI study's trace."""
    if kind == "margins":
        return [("safety_margins_distance", margin_figure(path))]
    runs = read(path, TWIN_COLUMNS, "seed")
    return [("parti_twin_errors", twin_error_figure(runs)), ("parti_twin_estimators", estimator_figure(runs))]
