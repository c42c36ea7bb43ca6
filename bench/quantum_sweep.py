#!/usr/bin/env python3
"""Run time against frame-time error for a range of global quanta (docs/quantum.md).

Runs `rtsim run` for each quantum (median wall time of --repeat runs) and reports the frame
time's relative error against quantum 0, the reference setting, and the overhead ratio to the
functional render of the same frame.

  bench/quantum_sweep.py [--rtsim build/rtsim] [--repeat 3] -- <rtsim run arguments>
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile

QUANTA = ["0 s", "100 ns", "1 us", "10 us", "100 us", "1 ms", "10 ms"]


def run(rtsim, args, quantum, out):
    cmd = [rtsim, "run", *args, "--quantum", quantum, "--overhead", "-q", "--out", out]
    subprocess.run(cmd, check=True)
    with open(f"{out}/stats.json") as f:
        return json.load(f)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--rtsim", default="build/rtsim")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("args", nargs=argparse.REMAINDER)
    a = p.parse_args()
    args = [x for x in a.args if x != "--"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for q in QUANTA:
            stats = [run(a.rtsim, args, q, f"{tmp}/q") for _ in range(a.repeat)]
            rows.append((q, stats[0]["simulated_time_s"],
                         statistics.median(s["wall_time_s"] for s in stats),
                         statistics.median(s["overhead_ratio"] for s in stats),
                         stats[0]["ray_latency_s"]["p50"]))
    ref = rows[0][1]
    print("| quantum | frame time (s) | error vs quantum 0 | wall time (s, median) | overhead ratio | ray latency p50 (s) |")
    print("|---|---:|---:|---:|---:|---:|")
    for q, t, wall, ratio, p50 in rows:
        err = abs(t - ref) / ref
        print(f"| {q} | {t:.6f} | {100 * err:.3f}% | {wall:.3f} | {ratio:.2f} | {p50:.3g} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
