#!/usr/bin/python3
"""The ray casters' workloads and the ring's traffic of Pixel-Planes 5's ray tracer
(`rtsim run --machine pxpl5-raytrace`), from stats.json (`pxpl5`, `modules`; docs/stats.md).

    /usr/bin/python3 analysis/pxpl5_workload.py out/run/stats.json workload.png
    /usr/bin/python3 analysis/pxpl5_workload.py out/run workload.png

Top: each ray caster's busy time normalised to the busiest, the bar graph VOL2 watched its load
balance with (Plate 4, seed 004 L366), with the regions each was given. Bottom: the bytes each
traffic class put on the token ring (headers included), beside the ring's utilisation.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

CLASSES = ["start", "request", "assign", "samples", "band", "pixels", "frame_done"]


def workload_series(stats):
    """(workloads, regions, class_bytes, ring_utilisation); InputProblem without a pxpl5 run."""
    p = stats.get("pxpl5")
    if not isinstance(p, dict) or not isinstance(p.get("caster_workload"), list):
        raise common.InputProblem("stats.json has no pxpl5.caster_workload (written by "
                                  "`rtsim run --machine pxpl5-raytrace`)")
    workloads = [float(x) for x in p["caster_workload"]]
    if not workloads:
        raise common.InputProblem("pxpl5.caster_workload is empty")
    modules = stats.get("modules", {})
    regions = [float(modules.get(f"caster{k}", {}).get("regions", 0.0))
               for k in range(len(workloads))]
    ring = modules.get("ring", {})
    class_bytes = {c: float(ring.get(f"bytes.{c}", 0.0)) for c in CLASSES}
    return workloads, regions, class_bytes, float(ring.get("utilization", 0.0))


def plot(workloads, regions, class_bytes, ring_util, title, out_path):
    plt = common.pyplot()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6.5))
    x = list(range(len(workloads)))
    top.bar(x, workloads, color="tab:blue")
    for xi, (w, n) in enumerate(zip(workloads, regions)):
        top.text(xi, w, f"{n:.0f}", ha="center", va="bottom", fontsize="x-small")
    top.set_ylim(0, 1.15)
    common.integer_axis(top.xaxis)
    top.set_xlabel("ray caster (the number over a bar: regions it was given)")
    top.set_ylabel("busy / busiest caster's")
    top.set_title(title, fontsize="medium")
    names = [c for c in CLASSES if class_bytes[c] > 0] or CLASSES
    bottom.barh(names, [class_bytes[c] / 1e6 for c in names], color="tab:green")
    bottom.set_xlabel(f"MB on the token ring (ring busy {100 * ring_util:.1f}% of the run)")
    fig.tight_layout()
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="pxpl5_workload.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine pxpl5-raytrace`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    workloads, regions, class_bytes, ring_util = workload_series(stats)
    p = stats["pxpl5"]
    title = args.title or (f"Ray casters' workloads: {len(workloads)} casters, "
                           f"{p.get('scheme', '?')} in {p.get('order', '?')} order, "
                           f"{stats.get('scene', '?')}")
    plot(workloads, regions, class_bytes, ring_util, title, args.out)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
