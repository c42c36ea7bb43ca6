#!/usr/bin/env python3
"""Wall time and peak memory of ullner-pipeline against the number of polygon processors N, and
its overhead over the functional render of the same frame (docs/benchmarks.md).

    scripts/pipeline_scale.py build/rtsim                      # N = 10 .. 100,000, 128x128
    scripts/pipeline_scale.py build/rtsim --engines 1000 10000 --repeats 5 --json scale.json
    scripts/pipeline_scale.py build/rtsim --model engines     # every processor a module

For each N: `rtsim run --machine ullner-pipeline -p pipeline.engines=N` on a scene of about N
polygons (builtin:ullner-sheets-10 for 10, builtin:ullner-random-N above), under
/usr/bin/time -v for the peak resident set, and `rtsim render --machine ullner-pipeline` (the
twin: the same brute-force search) on the same scene and size; medians of --repeats runs of
each. Prints a Markdown table: N, polygons, the run's simulation wall time (stats.json
wall_time_s) and whole-process elapsed time, peak RSS, the render's wall time and the ratio.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def scene_for(n):
    return "builtin:ullner-sheets-10" if n < 100 else f"builtin:ullner-random-{n}"


def timed(cmd):
    """(elapsed s, peak RSS KiB, stats.json) of one command writing into a fresh folder."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        r = subprocess.run(["/usr/bin/time", "-v"] + cmd + ["-q", "--out", out],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr[-2000:]}")
        rss = elapsed = None
        for line in r.stderr.splitlines():
            line = line.strip()
            if line.startswith("Maximum resident set size"):
                rss = int(line.split(":")[1])
            elif line.startswith("Elapsed (wall clock) time"):
                t = line.split(": ", 1)[1].split(":")
                elapsed = sum(float(x) * 60 ** i for i, x in enumerate(reversed(t)))
        with open(os.path.join(out, "stats.json")) as f:
            stats = json.load(f)
        return elapsed, rss, stats


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rtsim")
    ap.add_argument("--engines", type=int, nargs="+", default=[10, 100, 1000, 10000, 100000])
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--model", choices=["chain", "engines"], default="chain",
                    help="pipeline.model: the chain formula or a module per processor")
    ap.add_argument("--json", help="also write the measurements here")
    args = ap.parse_args()
    rows = []
    print("| N | polygons | run: simulation wall | run: process | peak RSS | render wall | "
          "ratio | simulated frame |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in args.engines:
        scene = scene_for(n)
        size = ["--width", str(args.size), "--height", str(args.size)]
        run = [args.rtsim, "run", "--machine", "ullner-pipeline", "--scene", scene,
               "-p", f"pipeline.engines={n}", "-p", f"pipeline.model={args.model}"] + size
        render = [args.rtsim, "render", "--machine", "ullner-pipeline", "--scene", scene,
                  "-p", f"pipeline.engines={n}"] + size
        runs = [timed(run) for _ in range(args.repeats)]
        renders = [timed(render) for _ in range(args.repeats)]
        sim = statistics.median(s["wall_time_s"] for _, _, s in runs)
        proc = statistics.median(e for e, _, _ in runs)
        rss = max(r for _, r, _ in runs)
        ren = statistics.median(s["wall_time_s"] for _, _, s in renders)
        row = {"engines": n, "scene": scene, "polygons": runs[0][2]["pipeline"]["polygons"],
               "run_wall_s": sim, "run_process_s": proc, "peak_rss_mib": rss / 1024.0,
               "render_wall_s": ren, "ratio": sim / ren,
               "simulated_time_s": runs[0][2]["simulated_time_s"]}
        rows.append(row)
        print(f"| {n:,} | {row['polygons']:,} | {sim:.3g} s | {proc:.3g} s | "
              f"{row['peak_rss_mib']:.0f} MiB | {ren:.3g} s | {row['ratio']:.2f} | "
              f"{row['simulated_time_s']:.4g} s |", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
