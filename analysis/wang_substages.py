#!/usr/bin/python3
"""The substages of Wang, Lewis & Hung's Bezier pipeline (`rtsim run --machine wang-bezier`):
what each costs a job against the pipeline cycle, and how busy its DSP pool was over the frame,
from stats.json (`wang.stage0`, `wang.substages`, `modules`; docs/stats.md).

    /usr/bin/python3 analysis/wang_substages.py out/run/stats.json substages.png
    /usr/bin/python3 analysis/wang_substages.py out/run substages.png

Top: each substage's time per job (stage 0's, then those of one loop stage, Table 4's rows,
seed 002 L436-L441) with the pipeline cycle, the slowest of them (one job enters a cycle); the
bottleneck is red, and each bar says how many DSPs do how many cycles. Bottom: the busy fraction
of each substage's DSP pool over the frame (time per job x jobs / frame time), beside the host's:
a pipeline whose pools idle while the host is busy is waiting for the host.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def substage_rows(stats):
    """[(name, dsps, cycles, time_s)] in pipeline order, the cycle (s), the jobs, the frame (s)
    and the host's busy fraction; InputProblem if stats.json has no wang section."""
    w = stats.get("wang")
    if not isinstance(w, dict) or not isinstance(w.get("substages"), dict):
        raise common.InputProblem("stats.json has no wang.substages (written by "
                                  "`rtsim run --machine wang-bezier`)")
    rows = []
    for part in ("stage0", "substages"):
        for name, s in (w.get(part) or {}).items():
            if not isinstance(s, dict) or "time_s" not in s:
                raise common.InputProblem(f"wang.{part}.{name}: expected an object with time_s")
            if part == "substages":
                label = f"loop.{name}"
            else:  # "split_u", or "stage0.split_u" in stats.json written before 2026-12-03
                label = name if name.startswith("stage0.") else f"stage0.{name}"
            rows.append((label, int(s.get("dsps", 0)), int(s.get("cycles", 0)),
                         float(s["time_s"])))
    if not rows:
        raise common.InputProblem("wang.substages is empty")
    cycle = float(w.get("cycle_s", max(r[3] for r in rows)))
    jobs = float(w.get("jobs", 0))
    frame = float(stats.get("simulated_time_s", 0.0))
    host = stats.get("modules", {}).get("host", {})
    host_busy = float(host.get("utilization", 0.0)) if isinstance(host, dict) else 0.0
    return rows, cycle, jobs, frame, host_busy


def busy_fractions(rows, jobs, frame):
    """Each substage's busy fraction over the frame: time per job x jobs / frame."""
    return [min(1.0, r[3] * jobs / frame) if frame > 0 else 0.0 for r in rows]


def draw(rows, cycle, jobs, frame, host_busy, loop_stages, title):
    """(fig, (top, bottom)): time per job against the cycle, in one unit (ns, µs, ms, s or h),
    and each pool's busy fraction over the frame."""
    plt = common.pyplot()
    names = [r[0] for r in rows]
    scale, unit = common.time_unit(max([r[3] for r in rows] + [cycle]))
    times = [r[3] * scale for r in rows]
    slowest = max(times)
    colors = ["tab:red" if t >= slowest * (1 - 1e-9) else "tab:blue" for t in times]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 7))
    y = list(range(len(rows)))[::-1]
    top.barh(y, times, color=colors)
    for yi, (name, dsps, cycles, _), t in zip(y, rows, times):
        what = f"{dsps} DSP{'s' if dsps != 1 else ''} x {cycles} cycles" if dsps else "ASIC"
        top.text(t, yi, f"  {what}", va="center", fontsize="x-small")
    top.axvline(cycle * scale, color="black", linestyle="--",
                label=f"pipeline cycle {cycle * scale:.4g} {unit} ({1 / cycle:,.0f} jobs/s)")
    top.set_yticks(y)
    top.set_yticklabels(names, fontsize="small")
    top.set_xlabel(f"time per job ({unit})")
    top.set_xlim(0, slowest * 1.45)
    top.set_title(title, fontsize="medium")
    busy = busy_fractions(rows, jobs, frame)
    bottom.barh(y, busy, color=colors)
    bottom.axvline(host_busy, color="tab:orange", linestyle="-.",
                   label=f"host busy {100 * host_busy:.0f}%")
    bottom.set_yticks(y)
    bottom.set_yticklabels(names, fontsize="small")
    bottom.set_xlim(0, 1.0)
    frame_scale, frame_unit = common.time_unit(frame)
    bottom.set_xlabel(f"busy fraction over the frame ({jobs:.0f} jobs in "
                      f"{frame * frame_scale:.3g} {frame_unit}; all {loop_stages} loop stages "
                      "alike)")
    fig.tight_layout()
    for ax in (top, bottom):
        common.place_legend(ax, fontsize="x-small")
    return fig, (top, bottom)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="wang_substages.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine wang-bezier`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    rows, cycle, jobs, frame, host_busy = substage_rows(stats)
    loop_stages = int(stats["wang"].get("loop_stages", 0))
    dsps = stats["wang"].get("dsps", "?")
    title = args.title or (f"Bezier pipeline substages: {loop_stages} loop stages, {dsps} DSPs, "
                           f"{stats.get('scene', '?')}")
    fig, _ = draw(rows, cycle, jobs, frame, host_busy, loop_stages, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
