#!/usr/bin/python3
"""Along the chain of Ullner's ray-tracing pipeline (`rtsim run --machine ullner-pipeline`):
each polygon processor's busy fraction, and what its work was worth, from stats.json
(`pipeline.along_chain`; docs/stats.md).

    /usr/bin/python3 analysis/chain_profile.py out/run/stats.json chain.png
    /usr/bin/python3 analysis/chain_profile.py out/run chain.png

Top: the busy fraction of the processors along the chain (every processor takes every ray for
one issue interval, so the line is flat: high when the chain sets the pace, low when the host
does, seed 000 L745). Bottom: per ray description, how often a processor overwrote it (found its
polygon closer than the carried t) and how often it gave the answer (the description left the
chain naming it) — the useful part of its work (L749: "most of the intersections being computed
at any one time will turn out to have no bearing on the appearance of the final image"). Spare
processors (dummy polygons) are shaded. For long chains stats.json averages runs of neighbouring
processors into at most 1000 points.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def chain_series(stats):
    """(first_engine, busy, overwrites, answers, engines, polygons) from stats.json;
    InputProblem if it has no pipeline.along_chain."""
    p = stats.get("pipeline")
    along = p.get("along_chain") if isinstance(p, dict) else None
    if not isinstance(along, dict):
        raise common.InputProblem("stats.json has no pipeline.along_chain (written by "
                                  "`rtsim run --machine ullner-pipeline`)")
    first = [int(x) for x in along.get("first_engine", [])]
    over = [float(x) for x in along.get("overwrites_per_description", [])]
    ans = [float(x) for x in along.get("answers_per_description", [])]
    if not (len(first) == len(over) == len(ans)) or not first:
        raise common.InputProblem(f"pipeline.along_chain: {len(first)} processors, {len(over)} "
                                  f"overwrite and {len(ans)} answer values (expected equal, > 0)")
    engines = int(along.get("engines", first[-1] + 1))
    polygons = int(p.get("polygons", engines))
    busy = float(along.get("busy_fraction", 0.0))
    return first, busy, over, ans, engines, polygons


def draw(first, busy, over, ans, engines, polygons, title):
    """(fig, (top, bottom)): busy fraction and worth along the chain, processors on x."""
    import numpy as np

    plt = common.pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True,
                                      gridspec_kw={"height_ratios": [1, 1.4]})
    x = np.asarray(first + [engines])
    for ax in (top, bottom):
        if polygons < engines:
            ax.axvspan(polygons, engines, color="0.9", label="dummy polygons", zorder=0)
        ax.grid(True, alpha=0.3)
    top.stairs(np.full(len(first), busy), x, color="tab:blue", linewidth=1.5,
               label=f"busy {busy:.3g}")
    top.set_ylim(0, 1.05)
    top.set_ylabel("busy fraction")
    bottom.stairs(np.asarray(over), x, color="tab:orange", label="overwrote the description")
    bottom.stairs(np.asarray(ans), x, color="tab:green", label="gave the answer")
    bottom.set_ylabel("per ray description")
    bottom.set_xlabel("processor along the chain")
    bottom.set_xlim(0, engines)
    common.integer_axis(bottom.xaxis)
    top.set_title(title)
    for ax in (top, bottom):
        common.place_legend(ax, fontsize="small")
    return fig, (top, bottom)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="chain_profile.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine ullner-pipeline`, or its "
                                  "folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    first, busy, over, ans, engines, polygons = chain_series(stats)
    title = args.title or (f"Along the chain: {engines} processors, {polygons} polygons, "
                           f"{stats.get('scene', '?')}")
    fig, _ = draw(first, busy, over, ans, engines, polygons, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
