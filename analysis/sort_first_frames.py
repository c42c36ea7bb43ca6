#!/usr/bin/python3
"""The frames of a sort-first run (`rtsim run --machine sort-first`), from stats.json
(`sort_first.per_frame`, docs/machines.md).

    /usr/bin/python3 analysis/sort_first_frames.py out/run/stats.json frames.png
    /usr/bin/python3 analysis/sort_first_frames.py out/run frames.png

Top: the share of the primitives migrated in each frame (the first, which redistributes the
random initial distribution, is drawn hollow and left out of the study's summary, seed 004
L562), with the summary's mean and 95th percentile. Middle: the bytes each frame handed to the
interconnect, by kind (redistribution, finished pixels, sort-last's partial images, control).
Bottom: each frame's time, and the busiest renderer over the mean renderer (the load balance
sort-first must manage, L548).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def frame_rows(stats):
    """[(frame, migrated %, {kind: bytes}, time_s, load imbalance)]; InputProblem without a
    sort_first.per_frame section."""
    sf = stats.get("sort_first")
    if not isinstance(sf, dict) or not isinstance(sf.get("per_frame"), list) or not sf["per_frame"]:
        raise common.InputProblem("stats.json has no sort_first.per_frame (written by "
                                  "`rtsim run --machine sort-first`)")
    rows = []
    for f in sf["per_frame"]:
        if not isinstance(f, dict) or "migrated_percent" not in f:
            raise common.InputProblem("sort_first.per_frame: expected objects with migrated_percent")
        rows.append((int(f.get("frame", len(rows))), float(f["migrated_percent"]),
                     {k: float(v) for k, v in f.get("bytes", {}).items()},
                     float(f.get("time_s", 0.0)), float(f.get("load_imbalance", 0.0))))
    return rows


def draw(rows, summary, title):
    plt = common.pyplot()
    fig, (ax_m, ax_b, ax_t) = plt.subplots(3, 1, figsize=(10, 9), sharex=True)
    frames = [r[0] for r in rows]
    ax_m.plot(frames[1:], [r[1] for r in rows[1:]], "o-", color="C0", markersize=3,
              label="migrated")
    ax_m.plot(frames[:1], [rows[0][1]], "o", mfc="none", color="C0",
              label="frame 0 (the random distribution's)")
    for key, style in (("mean", "--"), ("p95", ":")):
        if isinstance(summary.get(key), (int, float)):
            ax_m.axhline(summary[key], color="grey", linestyle=style,
                         label=f"{'mean' if key == 'mean' else '95th percentile'} "
                               f"{summary[key]:.3g} %")
    ax_m.set_yscale("log")
    common.log_axis(ax_m.yaxis)
    ax_m.set_ylabel("primitives migrated (%)")
    common.place_legend(ax_m, fontsize="x-small")
    groups = (("redistribution", ("redistribution",)), ("pixels", ("pixels",)),
              ("partial images", ("partial",)), ("control", ("view", "tally", "expected")))
    bottom = [0.0] * len(rows)
    for i, (label, kinds) in enumerate(groups):
        vals = [sum(r[2].get(k, 0.0) for k in kinds) / 1e3 for r in rows]
        if not any(vals):
            continue
        ax_b.bar(frames, vals, bottom=bottom, color=f"C{i}", label=label)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax_b.set_ylabel("bytes on the interconnect (kB)")
    common.place_legend(ax_b, fontsize="x-small")
    scale, unit = common.time_unit(max(r[3] for r in rows))
    ax_t.plot(frames, [r[3] * scale for r in rows], "o-", color="C3", markersize=3,
              label="frame time")
    ax_t.set_ylabel(f"frame time ({unit})")
    ax_l = ax_t.twinx()
    ax_l.plot(frames, [r[4] for r in rows], "s-", color="C4", markersize=3,
              label="busiest renderer / mean")
    ax_l.set_ylabel("busiest renderer / mean")
    ax_t.set_xlabel("frame")
    common.integer_axis(ax_t.xaxis)
    for ax in (ax_m, ax_b, ax_t):
        ax.grid(True, alpha=0.3)
    lines = ax_t.get_lines() + ax_l.get_lines()
    ax_t.legend(lines, [line.get_label() for line in lines], fontsize="x-small", loc="best")
    fig.suptitle(title, fontsize="small")
    fig.tight_layout()
    return fig


def main(argv):
    ap = argparse.ArgumentParser(
        prog="sort_first_frames.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine sort-first`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    rows = frame_rows(stats)
    sf = stats["sort_first"]
    title = args.title or (f"sort-{sf.get('sort', 'first')} on {sf.get('region_grid', '?')} "
                           f"regions ({sf.get('interconnect', '?')}), {stats.get('scene', '?')}, "
                           f"{len(rows)} frames")
    fig = draw(rows, sf.get("migrated_percent", {}), title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
