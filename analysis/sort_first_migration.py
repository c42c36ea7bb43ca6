#!/usr/bin/python3
"""Sort-first's coherence (configs/sweeps/sort-first-regions.toml; seed 004 L560-L577): the share
of primitives migrated a frame, frame by frame for each region grid at the study's 4.5 degrees a
frame (left), and its mean against the region count for each spin with the 95th percentile as a
bar (right), the PLB head's table (4.06 / 8.80 / 18.07 % at 4x4 / 8x8 / 16x16) marked. The frames
after the first are read from each point's stats.json (sort_first.per_frame); the first, which
redistributes the random initial distribution, is left out as the study does (L562).

    build/rtsim sweep configs/sweeps/sort-first-regions.toml --jobs 2 --out out/sort-first-regions
    /usr/bin/python3 analysis/sort_first_migration.py out/sort-first-regions docs/sort-first-migration.png

Prints a Markdown table: mean (95th percentile) % a frame, by region grid and spin.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402

# The PLB head's table (seed 004 L572-L577): regions a side -> mean %.
PLB = {4: 4.06, 8: 8.80, 16: 18.07}


def points(folder):
    """{spin: {side: (per-frame %, mean, p95)}} from the sweep's folder."""
    df = sweep_plot.ok_rows(sweep_plot.read_results(folder))
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    side_c = common.resolve_column(df.columns, "regions")
    spin_c = common.resolve_column(df.columns, "camera.spin")
    out = {}
    for _, r in df.iterrows():
        _, stats = common.read_stats(os.path.join(folder, str(r["dir"])))
        sf = stats.get("sort_first")
        if not isinstance(sf, dict) or "per_frame" not in sf:
            raise common.InputProblem(f"{r['dir']}: no sort_first.per_frame in its stats.json")
        frames = [f["migrated_percent"] for f in sf["per_frame"][1:]]
        summary = sf.get("migrated_percent", {})
        out.setdefault(common.to_number(r[spin_c]), {})[int(common.to_number(r[side_c]))] = (
            frames, summary.get("mean", float("nan")), summary.get("p95", float("nan")))
    return {k: dict(sorted(v.items())) for k, v in sorted(out.items())}


def plot(data, out_path):
    plt = common.pyplot()
    fig, (ax_f, ax_r) = plt.subplots(1, 2, figsize=(12, 4.8))
    spin = 4.5 if 4.5 in data else next(iter(data))
    for i, (side, (frames, _, _)) in enumerate(data[spin].items()):
        ax_f.plot(range(1, len(frames) + 1), frames, color=f"C{i}", label=f"{side}x{side}")
    ax_f.set_xlabel("frame (the first, the random distribution's, left out)")
    ax_f.set_ylabel("primitives migrated (%)")
    ax_f.set_title(f"frame by frame, spun {common.plain_number(spin)} degrees a frame",
                   fontsize="small")
    ax_f.grid(True, alpha=0.3)
    common.place_legend(ax_f, fontsize="x-small")
    for i, (s, sides) in enumerate(data.items()):
        xs = list(sides)
        means = [m for _, m, _ in sides.values()]
        p95 = [p for _, _, p in sides.values()]
        ax_r.errorbar(xs, means, yerr=[[0] * len(xs), [p - m for m, p in zip(means, p95)]],
                      color=f"C{i}", marker="o", capsize=3,
                      label=f"{common.plain_number(s)} degrees a frame (bar: 95th percentile)")
    ax_r.plot(list(PLB), list(PLB.values()), "k*", markersize=10,
              label="PLB head, 4.5 degrees (L572-L577)")
    ax_r.set_xscale("log", base=2)
    ax_r.set_yscale("log")
    common.log_axis(ax_r.xaxis, integer=True)
    common.log_axis(ax_r.yaxis)
    ax_r.set_xlabel("regions a side (N x N renderers)")
    ax_r.set_ylabel("primitives migrated a frame, mean (%)")
    ax_r.set_title("against the region grid", fontsize="small")
    ax_r.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    common.place_legend(ax_r, fontsize="x-small")
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="sort_first_migration.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="the sweep's --out folder (results and points/)")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    if not os.path.isdir(args.input):
        raise common.InputProblem(f"{args.input}: expected the sweep's --out folder")
    data = points(args.input)
    plot(data, args.out)
    sides = sorted({n for v in data.values() for n in v})
    print("| spin | " + " | ".join(f"{n}x{n}" for n in sides) + " |")
    print("|---|" + "---|" * len(sides))
    for s, v in data.items():
        cells = {n: f"{m:.2f} ({p:.2f})" for n, (_, m, p) in v.items()}
        print(f"| {common.plain_number(s)} | " + " | ".join(cells.get(n, "-") for n in sides) + " |")
    print("\n(mean % of primitives migrated a frame, 95th percentile in brackets)")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
