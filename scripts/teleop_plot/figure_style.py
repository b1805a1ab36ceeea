"""One size and look for every figure, and where it is written."""

import os

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as pyplot  # noqa: E402  (after the backend is chosen)

# every figure is WIDTH_PX x HEIGHT_PX (the tests check this)
DPI = 100
WIDTH_PX = 1200
HEIGHT_PX = 800


def new_figure(rows, title, sharex=True):
    """A figure of `rows` stacked axes (a list, even for one) under `title`."""
    fig, axes = pyplot.subplots(rows, 1, figsize=(WIDTH_PX / DPI, HEIGHT_PX / DPI), dpi=DPI, sharex=sharex,
                                squeeze=False, layout="constrained")
    fig.suptitle(title, fontsize=13)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
        ax.set_axisbelow(True)  # the grid behind bars and lines
    return fig, list(axes[:, 0])


def save(fig, out_dir, name):
    """Writes `fig` as out_dir/name.png, closes it and returns the path."""
    path = os.path.join(out_dir, name + ".png")
    fig.savefig(path, dpi=DPI)
    pyplot.close(fig)
    return path
