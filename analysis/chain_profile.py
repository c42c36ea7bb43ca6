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
processors into at most 1000 points. With `-p pipeline.model=engines` a third panel shows when a
few processors along the chain were busy over the frame (`along_chain.busy_windows`): the chain
filling as a diagonal from the first processor to the last, holds where a slow host's end stops
it (`host.result_slots`), and the drain.
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


def busy_windows(stats):
    """(engines, begin_s, window_s, rows) of pipeline.along_chain.busy_windows, or None when the
    run has none (pipeline.model = chain); InputProblem if it is malformed."""
    b = stats.get("pipeline", {}).get("along_chain", {}).get("busy_windows")
    if b is None:
        return None
    try:
        engines = [int(x) for x in b["engines"]]
        rows = [[float(v) for v in row] for row in b["busy"]]
        begin, width = float(b["begin_s"]), float(b["window_s"])
    except (KeyError, TypeError, ValueError) as e:
        raise common.InputProblem(f"pipeline.along_chain.busy_windows: {e}")
    if len(rows) != len(engines) or not rows or len({len(r) for r in rows}) != 1:
        raise common.InputProblem(f"pipeline.along_chain.busy_windows: {len(engines)} processors "
                                  f"and {len(rows)} rows of windows (expected equal, > 0, alike)")
    return engines, begin, width, rows


def draw(first, busy, over, ans, engines, polygons, title, windows=None):
    """(fig, axes): busy fraction and worth along the chain, processors on x; with `windows`
    (busy_windows()) a third panel, busy over time of the watched processors."""
    import numpy as np

    plt = common.pyplot()
    if windows is None:
        fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True,
                                          gridspec_kw={"height_ratios": [1, 1.4]})
    else:
        fig = plt.figure(figsize=(8, 8.5))
        grid = fig.add_gridspec(3, 1, height_ratios=[1, 1.4, 1.8], hspace=0.45)
        top = fig.add_subplot(grid[0])
        bottom = fig.add_subplot(grid[1], sharex=top)
        heat = fig.add_subplot(grid[2])
    x = np.asarray(first + [engines])
    for ax in (top, bottom):
        if polygons < engines:
            ax.axvspan(polygons, engines, color="0.9", label="dummy polygons", zorder=0)
        ax.grid(True, alpha=0.3)
    top.stairs(np.full(len(first), busy), x, color="tab:blue", linewidth=1.5,
               label=f"busy {100 * busy:.1f}%")
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
    if windows is None:
        return fig, (top, bottom)
    watched, begin, width, rows = windows
    data = np.asarray(rows)
    t0 = begin * 1e3
    t1 = (begin + width * data.shape[1]) * 1e3
    image = heat.imshow(data, aspect="auto", origin="lower", cmap="viridis", vmin=0.0, vmax=1.0,
                        extent=(t0, t1, -0.5, len(watched) - 0.5), interpolation="nearest")
    ticks = sorted(set([0, len(watched) // 2, len(watched) - 1]))
    heat.set_yticks(ticks)
    heat.set_yticklabels([str(watched[i]) for i in ticks])
    heat.set_ylabel("processor")
    heat.set_xlabel("simulated time (ms)")
    heat.set_title("busy over the frame, processors sampled along the chain", fontsize="medium")
    fig.colorbar(image, ax=heat, label="busy fraction", fraction=0.04, pad=0.02)
    return fig, (top, bottom, heat)


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
    fig, _ = draw(first, busy, over, ans, engines, polygons, title, busy_windows(stats))
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
