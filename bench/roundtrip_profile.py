#!/usr/bin/env python3
"""Where the round trip's CPU goes, variant by variant (docs/benchmarks.md, "Profile").

  python3 bench/roundtrip_profile.py [--bench build/default/bin/teleop_roundtrip_bench]
          [--variants fastdds,dds-udp,...] [--samples 3000] [--rate-hz 200] [--top 12] [--out DIR]

For each variant it runs teleop_roundtrip_bench twice:
  1. under valgrind --tool=callgrind (pinger and echo both, --trace-children=yes): the benchmark
     zeroes the counters when its measured window opens and dumps them when it closes
     (bench/roundtrip/profile_window.h), so the dump holds the round trips only. Instruction
     counts (Ir) are repeatable under load, unlike times. User space only: the kernel's share
     (system calls, wake-ups) is not in them, hence
  2. under strace -f -c at 1 kHz: the system calls of both processes per round trip (setup
     included, a few hundred calls over the run).
Printed per variant and process: instructions per round trip, by library, and the top functions
by their own (self) instructions per round trip. Exit status 0, 1 on a failed run, 2 on bad
arguments, 3 without valgrind or strace.
"""

import argparse
import collections
import os
import re
import shutil
import subprocess
import sys
import tempfile

SYSCALLS = ("futex", "sendto", "sendmsg", "recvfrom", "recvmsg", "setsockopt", "clock_nanosleep", "epoll_wait")


def parse_callgrind(path):
    """Self cost (Ir) per function and per object file of one callgrind dump.

    The format compresses names: "fn=(id) name" the first time, "fn=(id)" after. A "calls=" line
    is followed by one cost line that is the callee's inclusive cost: not the caller's own.
    """
    names = {}
    self_cost = collections.Counter()
    obj_of = {}
    current_fn = None
    current_ob = "?"
    skip_next_cost = False
    spec = re.compile(r"^(fn|ob|cob|cfn|fl|fi|fe|cfi|cfl)=\((\d+)\)(?: (.*))?$")
    with open(path, errors="replace") as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            m = spec.match(line)
            if m:
                kind, ident, name = m.groups()
                key = (kind.lstrip("c") if kind in ("cob", "cfn", "cfi", "cfl") else kind, ident)
                key = (("fl" if key[0] in ("fi", "fe", "fl") else key[0]), ident)
                if name is not None:
                    names[key] = name
                if kind == "fn":
                    current_fn = names.get(("fn", ident), ident)
                    obj_of.setdefault(current_fn, current_ob)
                elif kind == "ob":
                    current_ob = names.get(("ob", ident), ident)
                continue
            if line.startswith("calls="):
                skip_next_cost = True
                continue
            if line[0].isdigit() or line[0] in "+-*":
                if skip_next_cost:
                    skip_next_cost = False
                    continue
                parts = line.split()
                if len(parts) >= 2 and current_fn is not None:
                    self_cost[current_fn] += int(parts[-1])
    by_object = collections.Counter()
    for fn, cost in self_cost.items():
        by_object[os.path.basename(obj_of.get(fn, "?"))] += cost
    return self_cost, by_object


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def bench_args(args, variant, rate_hz):
    return [args.bench, "--variants", variant, "--samples", str(args.samples), "--warmup", str(args.warmup),
            "--rate-hz", str(rate_hz), "--timeout", "120"]


def window_counts(stdout_text, stderr_text, variant, samples):
    """Round trips in each process's window: the pinger's are the replies it got (its table's
    samples - lost), the echo says how many it sent back."""
    m = re.search(r"echo \S+: \d+ echoed \((\d+) after the warm-up\)", stderr_text)
    row = re.search(r"^" + re.escape(variant) + r"\s+(\d+)\s+(\d+)\s", stdout_text, re.M)
    pinger = int(row.group(1)) - int(row.group(2)) if row else samples
    return pinger, int(m.group(1)) if m else samples


def profile(args, variant, out_dir):
    d = os.path.join(out_dir, variant)
    os.makedirs(d, exist_ok=True)
    cmd = ["valgrind", "--tool=callgrind", "--trace-children=yes",
           "--callgrind-out-file=" + os.path.join(d, "callgrind.%p")] + bench_args(args, variant, args.rate_hz)
    r = run(cmd)
    if r.returncode != 0:
        sys.stderr.write(r.stdout[-2000:] + r.stderr[-2000:])
        raise RuntimeError(f"{variant}: the callgrind run failed")
    pinger_n, echo_n = window_counts(r.stdout, r.stderr, variant, args.samples)
    result = {}
    for name in sorted(os.listdir(d)):
        if not name.endswith(".1"):
            continue  # only the window's dump
        path = os.path.join(d, name)
        with open(path, errors="replace") as f:
            head = f.read(4000)
        role = "echo" if "--role echo" in head else "pinger"
        fns, objs = parse_callgrind(path)
        result[role] = (fns, objs, echo_n if role == "echo" else pinger_n)
    return result


def syscalls(args, variant, out_dir):
    path = os.path.join(out_dir, variant + ".strace")
    r = run(["strace", "-f", "-c", "-o", path] + bench_args(args, variant, 1000.0))
    if r.returncode != 0:
        raise RuntimeError(f"{variant}: the strace run failed")
    counts = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if len(parts) >= 5 and parts[-1] in SYSCALLS + ("total",):
                # % time, seconds, usecs/call, calls, [errors], syscall
                counts[parts[-1]] = int(parts[3])
    return counts, args.samples + args.warmup


def short(fn, width=96):
    fn = re.sub(r"\(.*\)( const)?$", "", fn)  # no argument lists
    fn = re.sub(r"eprosima::(fastrtps|fastdds)::(rtps|dds)::", "", fn)
    return fn if len(fn) <= width else fn[: width - 3] + "..."


def report(variant, prof, sys_counts, top, args_samples):
    print(f"\n=== {variant}")
    total_rt = 0.0
    for role in ("pinger", "echo"):
        if role not in prof:
            print(f"  {role}: no window dump")
            continue
        fns, objs, n = prof[role]
        total = sum(fns.values())
        total_rt += total / n
        print(f"  {role}: {total / n:,.0f} instructions per round trip ({n} round trips in its window, "
              f"{args_samples} sent)")
        libs = ", ".join(f"{o} {c / n:,.0f}" for o, c in objs.most_common(6))
        print(f"    by library: {libs}")
        for fn, c in fns.most_common(top):
            print(f"    {c / n:9,.0f}  {100.0 * c / total:5.1f}%  {short(fn)}")
    print(f"  both processes: {total_rt:,.0f} instructions per round trip")
    counts, n = sys_counts
    calls = ", ".join(f"{k} {counts[k] / n:.2f}" for k in SYSCALLS if k in counts)
    print(f"  system calls per round trip (both processes, strace -f -c over {n} round trips incl. setup): "
          f"{counts.get('total', 0) / n:.2f}: {calls}")
    return total_rt


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bench", default="build/default/bin/teleop_roundtrip_bench")
    p.add_argument("--variants", default="raw-udp,fastdds,dds-udp,dds-imp,dds-shm")
    p.add_argument("--samples", type=int, default=3000)
    p.add_argument("--warmup", type=int, default=200)
    p.add_argument("--rate-hz", type=float, default=200.0,
                   help="under callgrind (~50x slower) a 1 kHz ping-pong overruns and loses replies; "
                        "time-driven costs (announcements) are per second, so they weigh 5x more per "
                        "round trip at 200 Hz than at 1 kHz (a few hundred instructions)")
    p.add_argument("--top", type=int, default=12)
    p.add_argument("--out", help="keep the dumps here (default: a temporary folder)")
    args = p.parse_args()
    for tool in ("valgrind", "strace"):
        if shutil.which(tool) is None:
            print(f"roundtrip_profile: {tool} not found (apt-get install {tool})", file=sys.stderr)
            return 3
    if not os.access(args.bench, os.X_OK):
        print(f"roundtrip_profile: no benchmark at {args.bench} (build it: cmake --build --preset default)",
              file=sys.stderr)
        return 2
    out_dir = args.out or tempfile.mkdtemp(prefix="roundtrip_profile.")
    print(f"roundtrip_profile: {args.samples} round trips at {args.rate_hz:g} Hz per variant; dumps in {out_dir}")
    totals = {}
    try:
        for variant in args.variants.split(","):
            totals[variant] = report(variant, profile(args, variant, out_dir), syscalls(args, variant, out_dir),
                                     args.top, args.samples)
    except RuntimeError as e:
        print(f"roundtrip_profile: {e}", file=sys.stderr)
        return 1
    if "fastdds" in totals:
        print("\ninstructions per round trip / bare Fast DDS's: " +
              ", ".join(f"{v} {t / totals['fastdds']:.2f}x" for v, t in totals.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
