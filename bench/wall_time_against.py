#!/usr/bin/env python3
"""Wall time of two rtsim builds on the same runs, alternately: the median of N runs each.

    bench/wall_time_against.py OLD/rtsim build/rtsim [N] [FILTER]

This machine is shared and noisy: the two builds run one after the other, N times each, and the
medians of the whole process's elapsed time are compared (docs/benchmarks.md). FILTER keeps the
runs whose label contains it. Prints a Markdown table.
"""
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

old, new = sys.argv[1], sys.argv[2]
N = int(sys.argv[3]) if len(sys.argv) > 3 else 5
S = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "scenes") + "/"
cases = [
 ("ullner-peripheral brute, ullner-cubes 256", "--machine ullner-peripheral --scene builtin:ullner-cubes --width 256 --height 256"),
 ("ullner-peripheral grid 11, random-1000 512", "--machine ullner-peripheral --scene builtin:ullner-random-1000 -p peripheral.grid.divisions=11 --width 512 --height 512"),
 ("gaudet-pert 8 PERTs, npp-412 256", "--machine gaudet-pert --scene builtin:npp-412 -p pert_count=8 --width 256 --height 256"),
 ("gaudet-pert 2 PERTs, teapot-s2 128", f"--machine gaudet-pert --scene {S}teapot-s2.nff -p pert_count=2 --width 128 --height 128"),
 ("vax-750 teapot-s2 256", f"--machine vax-750 --scene {S}teapot-s2.nff --width 256 --height 256"),
 ("ullner-array 8x8, ullner-cubes 128", "--machine ullner-array --scene builtin:ullner-cubes --width 128 --height 128"),
 ("ullner-pipeline ullner-cubes 128", "--machine ullner-pipeline --scene builtin:ullner-cubes --width 128 --height 128"),
 ("wang-bezier teapot 96", "--machine wang-bezier --scene builtin:teapot --width 96 --height 96"),
 ("pxpl5-raytrace rows, default 256", "--machine pxpl5-raytrace --scene builtin:default -p assign.scheme=rows --width 256 --height 256"),
]
if len(sys.argv) > 4: cases = [c for c in cases if sys.argv[4] in c[0]]
OUT = tempfile.mkdtemp(prefix="rtsim-wall-")


def run(binary, args):
    t = time.perf_counter()
    subprocess.run([binary, "run"] + shlex.split(args) + ["-q", "--out", OUT], check=True,
                   capture_output=True)
    return time.perf_counter() - t



print("| run | old | new | change |\n|---|---:|---:|---:|")
for name, args in cases:
    a, b = [], []
    for i in range(N):
        a.append(run(old, args)); b.append(run(new, args))
    ma, mb = statistics.median(a), statistics.median(b)
    print(f"| {name} | {ma:.3f} s | {mb:.3f} s | {100*(mb/ma-1):+.1f}% |", flush=True)
