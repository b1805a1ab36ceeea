"""Figures of teleop runs (docs/plots.md); `teleop plot` and `teleop experiment` run this.

  python3 scripts/teleop_plot run RUN_DIR [OUT_DIR] [--leader NODE --window LABEL=BEGIN,END ...]
                                                       the traces of one run (<node>.csv) -> OUT_DIR/*.png
  python3 scripts/teleop_plot recording CSV_DIR [OUT_DIR]
                                                       a recording exported by `teleop bag export` -> OUT_DIR/<topic>_*.png
  python3 scripts/teleop_plot results CSV [OUT_DIR]     an experiment's results -> OUT_DIR/<csv name>_<metric>.png
  python3 scripts/teleop_plot hand TRACE_CSV [OUT_DIR]  the hand study's trace -> OUT_DIR/hand_tip_force.png, hand_joints.png
  python3 scripts/teleop_plot fidelity TRACE_CSV SEGMENTS_CSV [OUT_DIR]
                                                       the fidelity study's -> OUT_DIR/fidelity_<sequence>_*.png
  python3 scripts/teleop_plot parti margins|twin TRACE_CSV [OUT_DIR]
                                                       a PARTI study's -> OUT_DIR/safety_margins_*.png, parti_twin_*.png
  python3 scripts/teleop_plot wiping WIPES_CSV TRACE_CSV [OUT_DIR]
                                                       the wiping study's -> OUT_DIR/wiping_*.png

Exit status: 0 done (figures whose columns a run lacks are skipped with a message), 1 an error
(no trace in the dir, a file that cannot be read), 2 bad arguments, 3 no matplotlib.
"""

import argparse
import os
import sys

EXIT_ERROR, EXIT_NO_MATPLOTLIB = 1, 3


def window(text):
    """LABEL=BEGIN,END -> (label, (begin, end))."""
    try:
        label, span = text.split("=", 1)
        begin, end = (float(v) for v in span.split(","))
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"{text}: expected LABEL=BEGIN,END (seconds)") from e
    return label, (begin, end)


def limit(text):
    """METRIC=VALUE -> (metric, value)."""
    try:
        metric, value = text.split("=", 1)
        return metric, float(value)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"{text}: expected METRIC=VALUE") from e


def main():
    parser = argparse.ArgumentParser(prog="teleop_plot", description="PNG figures of teleop runs")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="the figures of one run's traces")
    run.add_argument("run_dir")
    run.add_argument("out_dir", nargs="?", help="default: RUN_DIR")
    run.add_argument("--leader", help="the node whose operator's start the marks count from (its operator_s column)")
    run.add_argument("--window", action="append", default=[], type=window, metavar="LABEL=BEGIN,END",
                     help="shade this window, in seconds after the operator's start (an experiment's hold window)")
    recording = commands.add_parser("recording", help="the figures of a recording exported as CSV")
    recording.add_argument("csv_dir")
    recording.add_argument("out_dir", nargs="?", help="default: CSV_DIR")
    results = commands.add_parser("results", help="one figure per metric of an experiment's results CSV")
    results.add_argument("csv")
    results.add_argument("out_dir", nargs="?", help="default: the CSV's folder")
    results.add_argument("--limit", action="append", default=[], type=limit, metavar="METRIC=VALUE",
                         help="draw this metric's limit of the stability verdict (stable at or below it)")
    hand = commands.add_parser("hand", help="the hand study's figures from its trace CSV")
    hand.add_argument("csv")
    hand.add_argument("out_dir", nargs="?", help="default: the CSV's folder")
    fidelity = commands.add_parser("fidelity", help="the fidelity study's figures from its trace and segments CSVs")
    fidelity.add_argument("csv")
    fidelity.add_argument("segments")
    fidelity.add_argument("out_dir", nargs="?", help="default: the CSV's folder")
    parti = commands.add_parser("parti", help="a PARTI study's figures from its trace CSV")
    parti.add_argument("kind", choices=("margins", "twin"))
    parti.add_argument("csv")
    parti.add_argument("out_dir", nargs="?", help="default: the CSV's folder")
    wiping = commands.add_parser("wiping", help="the wiping study's figures from its wipes and trace CSVs")
    wiping.add_argument("csv")
    wiping.add_argument("trace")
    wiping.add_argument("out_dir", nargs="?", help="default: the CSV's folder")
    args = parser.parse_args()
    try:
        import matplotlib  # noqa: F401  (only to say clearly that it is missing)
    except ImportError:
        print(f"teleop plot: {sys.executable} has no matplotlib: apt-get install python3-matplotlib "
              "(or scripts/setup.sh)", file=sys.stderr)
        return EXIT_NO_MATPLOTLIB
    # imported here: they load matplotlib
    import figure_style
    from fidelity_figures import FidelityTraceError, fidelity_figures
    from hand_figures import HandTraceError, hand_figures
    from parti_figures import PartiTraceError, parti_figures
    from recording_figures import RecordingCsvError, recording_figures
    from results_figures import ResultsError, results_figures
    from run_figures import FIGURES, Skip
    from run_traces import Run, TraceError
    from wiping_figures import WipingCsvError, wiping_figures

    def write(figures, out_dir, prefix=""):
        os.makedirs(out_dir, exist_ok=True)
        for name, fig in figures:
            print(f"teleop plot: wrote {figure_style.save(fig, out_dir, prefix + name)}")

    try:
        if args.command == "run":
            traces = Run(args.run_dir)
            if args.leader:
                origin = traces.mark(args.leader, args.window)
                marks = ", ".join(f"{label} {b:g}-{e:g} s" for label, (b, e) in args.window)
                print(f"teleop plot: no trace of {args.leader} to mark the operator's start on" if origin is None
                      else f"teleop plot: marked the operator's start at {origin:.3f} s"
                           + (f" and {marks} after it" if marks else "") + f" ({args.run_dir})")
            for name, figure in FIGURES:
                try:
                    write(figure(traces), args.out_dir or args.run_dir)
                except Skip as why:
                    print(f"teleop plot: skipped {name}: {why} ({args.run_dir})")
        elif args.command == "recording":
            write(recording_figures(args.csv_dir), args.out_dir or args.csv_dir)
        elif args.command == "fidelity":
            write(fidelity_figures(args.csv, args.segments), args.out_dir or os.path.dirname(os.path.abspath(args.csv)))
        elif args.command == "parti":
            write(parti_figures(args.kind, args.csv), args.out_dir or os.path.dirname(os.path.abspath(args.csv)))
        elif args.command == "wiping":
            write(wiping_figures(args.csv, args.trace), args.out_dir or os.path.dirname(os.path.abspath(args.csv)))
        elif args.command == "hand":
            write(hand_figures(args.csv), args.out_dir or os.path.dirname(os.path.abspath(args.csv)))
        else:
            stem = os.path.splitext(os.path.basename(args.csv))[0]
            out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.csv))
            write(results_figures(args.csv, stem, dict(args.limit)), out_dir, stem + "_")
    except (TraceError, ResultsError, HandTraceError, FidelityTraceError, PartiTraceError, WipingCsvError,
            RecordingCsvError, OSError) as e:
        print(f"teleop plot: {e}", file=sys.stderr)
        return EXIT_ERROR
    return 0


if __name__ == "__main__":
    sys.exit(main())
