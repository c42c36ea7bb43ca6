#!/usr/bin/env python3
"""Wall time of two rtsim builds on the same runs, alternately: the median of N runs each.

    bench/wall_time_against.py OLD/rtsim build/rtsim [--repeat N] [--size S] [--all] [--machine M]

The runs are each machine's registered benchmark runs (`rtsim list machines --format json` of the
new build; the first of each, or all with --all), at S x S (default 256) unless the run sets its
size. This machine is shared and noisy: the two builds run one after the other, N times each
(default 5), and the medians of the whole process's elapsed time are compared
(docs/benchmarks.md). Prints a Markdown table.
"""
import argparse
import json
import shlex
import statistics
import subprocess
import tempfile
import time


def benchmark_runs(rtsim, take_all, only):
    p = subprocess.run([rtsim, "list", "machines", "--format", "json"], capture_output=True,
                       text=True, check=True)
    for m in json.loads(p.stdout):
        if only and m["name"] not in only:
            continue
        runs = m.get("benchmark_runs", [])
        for r in runs if take_all else runs[:1]:
            yield m["name"], shlex.split(r)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--all", action="store_true", help="every benchmark run, not each first one")
    ap.add_argument("--machine", action="append", help="only this machine (repeatable)")
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="rtsim-wall-")

    def run(binary, machine, args):
        size = [] if "--width" in args else ["--width", str(a.size), "--height", str(a.size)]
        t = time.perf_counter()
        subprocess.run([binary, "run", "--machine", machine, *args, *size, "-q", "--out", out],
                       check=True, capture_output=True)
        return time.perf_counter() - t

    print("| run | old | new | change |\n|---|---:|---:|---:|")
    for machine, args in benchmark_runs(a.new, a.all, a.machine):
        old, new = [], []
        for _ in range(a.repeat):
            old.append(run(a.old, machine, args))
            new.append(run(a.new, machine, args))
        mo, mn = statistics.median(old), statistics.median(new)
        label = machine + " " + " ".join(args)
        print(f"| `{label}` | {mo:.3f} s | {mn:.3f} s | {100 * (mn / mo - 1):+.1f}% |", flush=True)


if __name__ == "__main__":
    main()
