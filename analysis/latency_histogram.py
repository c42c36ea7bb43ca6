#!/usr/bin/python3
"""Histogram of per-ray latency from a run's stats.json (`ray_latency_s`: from the ray
entering the machine's ray queue until the host has its answer; docs/stats.md).

    /usr/bin/python3 analysis/latency_histogram.py out/run/stats.json latency.png
    /usr/bin/python3 analysis/latency_histogram.py out/run latency.png --linear

stats.json holds the histogram rtsim recorded (`histogram.edges_s`, `histogram.counts`: 4
log-spaced buckets per octave) and the exact `mean`, `p50`, `p99` and `max`, which are drawn as
vertical lines. The x axis is logarithmic, as the buckets are, unless --linear.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def histogram_series(stats):
    """(edges_s, counts, marks) as drawn; marks = {"mean": s, "p50": s, "p99": s, "max": s}
    for those present. InputProblem if stats.json has no ray latency."""
    lat = stats.get("ray_latency_s")
    if not isinstance(lat, dict):
        raise common.InputProblem("stats.json has no ray_latency_s (written by `rtsim run`)")
    marks = {k: float(lat[k]) for k in ("mean", "p50", "p99", "max") if common.finite(lat.get(k))}
    hist = lat.get("histogram") or {}
    edges = [float(e) for e in hist.get("edges_s", [])]
    counts = [int(c) for c in hist.get("counts", [])]
    if counts and len(edges) != len(counts) + 1:
        raise common.InputProblem(f"ray_latency_s.histogram: {len(edges)} edges for "
                                  f"{len(counts)} buckets (expected one more edge)")
    return edges, counts, marks


def draw(edges, counts, marks, count, title, log_x=True):
    """(fig, ax): the buckets and the marks, latency in one unit (ns, µs, ms, s or h)."""
    import numpy as np

    plt = common.pyplot()
    fig, ax = plt.subplots(figsize=(7, 4))
    if counts and sum(counts) > 0:
        scale, unit = common.time_unit(max(edges))
        e = np.asarray(edges) * scale
        ax.stairs(np.asarray(counts), e, fill=True, alpha=0.6, label=f"{count} rays")
        styles = {"mean": ("k", "-"), "p50": ("tab:blue", "--"), "p99": ("tab:red", "--"),
                  "max": ("tab:gray", ":")}
        for name, value in marks.items():
            color, ls = styles[name]
            ax.axvline(value * scale, color=color, linestyle=ls, linewidth=1.2,
                       label=f"{name} {value * scale:.4g} {unit}")
        if log_x and e[0] > 0:
            ax.set_xscale("log")
            common.log_axis(ax.xaxis)
        common.integer_axis(ax.yaxis)
        ax.set_xlabel(f"ray latency ({unit})")
        ax.set_ylabel("rays")
        ax.grid(True, alpha=0.3)
        common.place_legend(ax, fontsize="small")
    else:
        ax.text(0.5, 0.5, "no ray latency recorded", ha="center", va="center",
                transform=ax.transAxes)
        ax.set_axis_off()
    ax.set_title(title)
    return fig, ax


def main(argv):
    ap = argparse.ArgumentParser(
        prog="latency_histogram.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--linear", action="store_true", help="linear latency axis")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    edges, counts, marks = histogram_series(stats)
    count = int(stats["ray_latency_s"].get("count", sum(counts)))
    title = args.title or (f"Ray latency: {stats.get('machine', '?')} on "
                           f"{stats.get('scene', '?')}")
    fig, _ = draw(edges, counts, marks, count, title, log_x=not args.linear)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
