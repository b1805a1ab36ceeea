#!/usr/bin/env python3
"""How the transport's cost grows (docs/benchmarks.md, "How cost grows").

  python3 bench/roundtrip_scaling.py [--build build/default] [--samples 5000] [--out DIR]
                                     [--skip-demo] [--demo-duration 20]

Runs teleop_roundtrip_bench at 1 kHz along three axes, one at a time from the base point (7 joints,
1 topic, 1 node pair): joints per sample (1, 7, 32), topics per node (1, 5, 20, 50: every topic
written each cycle and echoed), node pairs on this host (1, 2, 4, 8 benchmark instances at once,
each on its own DDS domain). Each point measures raw UDP, bare Fast DDS and the teleop transport in one
run. Then it launches the demo scenario (`teleop launch config/scenarios/demo.yaml --duration D`)
and reads each node's CPU time from /proc over the middle of the run.

Writes OUT/scaling.csv (every benchmark row, with the axis and its value), OUT/demo_cpu.csv,
OUT/scaling.md (the tables as in docs/benchmarks.md) and OUT/scaling.png. Exit status 0, 1 on a
failed run, 3 without matplotlib (the tables are written anyway).
"""

import argparse
import csv
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VARIANTS = "raw-udp,fastdds,dds-udp"
# the last point of topics and pairs goes past the 1-5-20 and 1-2-4 of issue 23 to find the knee
AXES = [("joints", [1, 7, 32]), ("topics", [1, 5, 20, 50]), ("pairs", [1, 2, 4, 8])]


def load1():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def bench_cmd(args, domain, summary, joints=7, topics=1):
    return [os.path.join(args.build, "bin", "teleop_roundtrip_bench"), "--variants", VARIANTS, "--samples",
            str(args.samples), "--domain", str(domain), "--joints", str(joints), "--topics", str(topics),
            "--summary-csv", summary]


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def run_point(args, axis, value, tmp):
    """One point of an axis: its benchmark rows (for pairs: every instance's), tagged."""
    joints = value if axis == "joints" else 7
    topics = value if axis == "topics" else 1
    instances = value if axis == "pairs" else 1
    procs, files = [], []
    for i in range(instances):
        summary = os.path.join(tmp, f"{axis}_{value}_{i}.csv")
        if os.path.exists(summary):
            os.remove(summary)
        files.append(summary)
        log = open(os.path.join(tmp, f"{axis}_{value}_{i}.log"), "w")
        procs.append((subprocess.Popen(bench_cmd(args, 80 + i, summary, joints, topics), stdout=log,
                                       stderr=subprocess.STDOUT), log))
    for p, log in procs:
        p.wait()
        log.close()
        if p.returncode != 0:
            raise RuntimeError(f"{axis}={value}: a benchmark failed, see {log.name}")
    rows = []
    for i, path in enumerate(files):
        for r in read_rows(path):
            r.update(axis=axis, value=str(value), instance=str(i))
            rows.append(r)
    return rows


def node_pids(launcher_pid):
    """The launcher's children (the nodes), by name."""
    pids = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        name = stat[stat.index("(") + 1: stat.rindex(")")]
        fields = stat[stat.rindex(")") + 2:].split()
        if int(fields[1]) == launcher_pid:
            pids[name] = int(entry)
    return pids


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def demo_cpu(args, tmp):
    """Each node's share of one core over the middle of a demo run (from 3 s to 2 s before the end)."""
    cmd = [os.path.join(args.build, "bin", "teleop"), "launch", os.path.join(ROOT, "config/scenarios/demo.yaml"),
           "--duration", str(args.demo_duration)]
    log = open(os.path.join(tmp, "demo.log"), "w")
    launcher = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=tmp)
    try:
        time.sleep(3.0)
        pids = node_pids(launcher.pid)
        pids["teleop (launcher)"] = launcher.pid
        t0, c0 = time.monotonic(), {n: cpu_seconds(p) for n, p in pids.items()}
        time.sleep(max(1.0, args.demo_duration - 5.0))
        t1, c1 = time.monotonic(), {n: cpu_seconds(p) for n, p in pids.items()}
        load = load1()
    finally:
        launcher.wait()
        log.close()
    if launcher.returncode != 0:
        raise RuntimeError(f"the demo failed, see {log.name}")
    return [{"process": n, "cpu_percent_of_one_core": f"{100.0 * (c1[n] - c0[n]) / (t1 - t0):.1f}",
             "window_s": f"{t1 - t0:.1f}", "load1": f"{load:.2f}"} for n in sorted(pids)]


def aggregate(rows, axis, value, variant):
    """A point's figures for one variant: the mean over the instances (pairs), and the total CPU
    share of one core at the point's sample rate."""
    rs = [r for r in rows if r["axis"] == axis and r["value"] == str(value) and r["variant"] == variant]
    if not rs:
        return None
    mean = lambda k: sum(float(r[k]) for r in rs) / len(rs)  # noqa: E731
    cpu = mean("cpu_us_per_rt")
    samples_per_s = float(rs[0]["rate_hz"]) * int(rs[0]["topics"])
    return {"p50": mean("p50_us"), "p99": mean("p99_us"), "cpu": cpu,
            "share": cpu * samples_per_s * len(rs) / 1e4, "payload": rs[0]["payload_bytes"], "load": mean("load1")}


def markdown(rows, demo, command):
    out = [f"`{command}`", "",
           "| axis | value | payload B | variant | p50 µs | p99 µs | CPU µs per sample round trip | CPU % of one core (all pairs) | load |",
           "|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for axis, values in AXES:
        for v in values:
            for variant in VARIANTS.split(","):
                a = aggregate(rows, axis, v, variant)
                if a:
                    out.append(f"| {axis} | {v} | {a['payload']} | {variant} | {a['p50']:.1f} | {a['p99']:.1f} | "
                               f"{a['cpu']:.1f} | {a['share']:.1f} | {a['load']:.2f} |")
    if demo:
        out += ["", "| demo process | CPU % of one core | window s | load |", "|---|---:|---:|---:|"]
        out += [f"| {d['process']} | {d['cpu_percent_of_one_core']} | {d['window_s']} | {d['load1']} |" for d in demo]
    return "\n".join(out) + "\n"


def figure(rows, demo, path, command):
    sys.path.insert(0, os.path.join(ROOT, "scripts", "teleop_plot"))
    from figure_style import DPI, HEIGHT_PX, WIDTH_PX  # noqa: E402
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 4, figsize=(WIDTH_PX / DPI, HEIGHT_PX / DPI), dpi=DPI, layout="constrained")
    fig.suptitle("Round trip leader → follower → leader at 1 kHz: how cost grows\n" + command, fontsize=10)
    colors = {"raw-udp": "tab:gray", "fastdds": "tab:blue", "dds-udp": "tab:red"}
    for col, (axis, values) in enumerate(AXES):
        for variant in VARIANTS.split(","):
            pts = [(v, aggregate(rows, axis, v, variant)) for v in values]
            pts = [(v, a) for v, a in pts if a]
            xs = [v for v, _ in pts]
            axes[0][col].plot(xs, [a["p50"] for _, a in pts], "o-", color=colors[variant], label=f"{variant} p50")
            axes[0][col].plot(xs, [a["p99"] for _, a in pts], "x--", color=colors[variant], alpha=0.5,
                              label=f"{variant} p99")
            axes[1][col].plot(xs, [a["cpu"] for _, a in pts], "o-", color=colors[variant], label=variant)
        axes[0][col].set_title({"joints": "joints per sample", "topics": "topics per node (each at 1 kHz)",
                                "pairs": "node pairs on the host"}[axis], fontsize=10)
        axes[0][col].set_yscale("log")
        axes[0][col].set_ylabel("RTT µs")
        axes[1][col].set_ylabel("CPU µs per sample round trip")
        axes[1][col].set_xlabel(axis)
        for ax in (axes[0][col], axes[1][col]):
            ax.set_xticks(values)
            ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=7)
    axes[1][0].legend(fontsize=7)
    if demo:
        names = [d["process"] for d in demo]
        axes[0][3].barh(names, [float(d["cpu_percent_of_one_core"]) for d in demo], color="tab:green")
        axes[0][3].set_title("demo scenario, 1 kHz", fontsize=10)
        axes[0][3].set_xlabel("CPU % of one core")
        axes[0][3].grid(True, alpha=0.3)
    else:
        axes[0][3].axis("off")
    # the whole load of each point: where the two cores run out
    labels, shares = [], {v: [] for v in VARIANTS.split(",")}
    for axis, values in AXES:
        for v in values:
            labels.append(f"{axis[0]}{v}")
            for variant in shares:
                a = aggregate(rows, axis, v, variant)
                shares[variant].append(a["share"] if a else 0.0)
    width = 0.8 / len(shares)
    for k, (variant, ys) in enumerate(shares.items()):
        axes[1][3].bar([i + (k - 1) * width for i in range(len(labels))], ys, width, color=colors[variant],
                       label=variant)
    axes[1][3].set_xticks(range(len(labels)), labels, rotation=90, fontsize=8)
    axes[1][3].set_ylabel("CPU % of one core, all processes")
    axes[1][3].set_title("whole load (j joints, t topics, p pairs)", fontsize=10)
    axes[1][3].grid(True, alpha=0.3)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build", "default"))
    p.add_argument("--samples", type=int, default=5000)
    p.add_argument("--out", default=os.path.join(ROOT, "build", "default", "scaling"))
    p.add_argument("--skip-demo", action="store_true")
    p.add_argument("--demo-duration", type=float, default=20.0)
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    command = "python3 bench/roundtrip_scaling.py " + " ".join(sys.argv[1:])
    rows, demo = [], []
    try:
        for axis, values in AXES:
            for v in values:
                print(f"{axis} = {v} (load {load1():.2f}) ...", flush=True)
                rows += run_point(args, axis, v, args.out)
        if not args.skip_demo:
            print(f"demo scenario for {args.demo_duration:g} s (load {load1():.2f}) ...", flush=True)
            demo = demo_cpu(args, args.out)
    except RuntimeError as e:
        print(f"roundtrip_scaling: {e}", file=sys.stderr)
        return 1
    fields = ["axis", "value", "instance"] + [k for k in rows[0] if k not in ("axis", "value", "instance")]
    with open(os.path.join(args.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    if demo:
        with open(os.path.join(args.out, "demo_cpu.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(demo[0]))
            w.writeheader()
            w.writerows(demo)
    table = markdown(rows, demo, command)
    with open(os.path.join(args.out, "scaling.md"), "w") as f:
        f.write(table)
    print(table)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("roundtrip_scaling: no matplotlib (apt-get install python3-matplotlib): no figure", file=sys.stderr)
        return 3
    figure(rows, demo, os.path.join(args.out, "scaling.png"), command)
    print(f"figure: {os.path.join(args.out, 'scaling.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
