#!/usr/bin/python3
"""VOL2's Fig. 9 (seed 004 L369-L371) from pxpl5-raytrace: the frame rate of sample rows against
adaptive sample squares as the scene's screen coverage falls (configs/sweeps/pxpl5-rows-squares.toml:
the eye backs away along its line of sight, camera.distance). VOL2: rows are better at low
coverage, squares at full screen, with more even rates over image sizes.

    build/rtsim sweep configs/sweeps/pxpl5-rows-squares.toml --out out/rows-squares
    /usr/bin/python3 analysis/pxpl5_rows_squares.py out/rows-squares out/rows-squares/fig9.png

The abscissa is the coverage the rows measure (a ray every 4 x 4 pixels, uniform); adaptive
squares cast more rays where the scene is, so their own count overstates it. The ordinate is the
last frame's rate, the frame whose squares went out in descending cost of the one before (L360).
Prints the table and the coverage where the two cross.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402


def table(df):
    """{distance: {"coverage": rows' coverage, "rows": fps, "squares": fps}}, sorted."""
    df = sweep_plot.ok_rows(df)
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    scheme = common.resolve_column(df.columns, "assign.scheme")
    dist = common.resolve_column(df.columns, "camera.distance")
    rate = common.resolve_column(df.columns, "pxpl5.last_frame_per_second")
    cover = common.resolve_column(df.columns, "pxpl5.screen_coverage")
    out = {}
    for _, r in df.iterrows():
        d = common.to_number(r[dist])
        row = out.setdefault(d, {})
        row[str(r[scheme])] = common.to_number(r[rate])
        if str(r[scheme]) == "rows":
            row["coverage"] = common.to_number(r[cover])
    rows = {d: v for d, v in sorted(out.items()) if {"rows", "squares", "coverage"} <= v.keys()}
    if not rows:
        raise common.InputProblem("the sweep needs assign.scheme rows and squares at each "
                                  "camera.distance")
    return rows


def crossing(rows):
    """The coverage between the last distance where squares win and the first where rows do."""
    items = list(rows.values())
    for a, b in zip(items, items[1:]):
        if a["squares"] >= a["rows"] and b["rows"] > b["squares"]:
            return (a["coverage"], b["coverage"])
    return None


def plot(rows, out_path):
    plt = common.pyplot()
    cov = [v["coverage"] for v in rows.values()]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(cov, [v["rows"] for v in rows.values()], marker="o",
            label="sample rows, a ray every 4 x 4 (L352)")
    ax.plot(cov, [v["squares"] for v in rows.values()], marker="s",
            label="sample squares, 16 x 16 refined to 4 x 4 (L360-L362)")
    for (d, v) in rows.items():
        ax.annotate(f"{d:g}x", (v["coverage"], v["rows"]), textcoords="offset points",
                    xytext=(0, 6), fontsize="x-small", ha="center", color="grey")
    ax.set_xscale("log")
    ax.set_xticks([0.02, 0.05, 0.1, 0.2, 0.5, 1.0])
    ax.set_xticklabels(["2%", "5%", "10%", "20%", "50%", "100%"])
    ax.set_xlabel("screen coverage (the rows' rays that hit; grey: camera.distance)")
    ax.set_ylabel("frames per second (the second frame)")
    ax.set_title("pxpl5-raytrace, SPD teapot, 640 x 512, 16 casters + 4 compositors + master "
                 "(VOL2 Fig. 9)", fontsize="small")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    common.place_legend(ax, fontsize="small")
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="pxpl5_rows_squares.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.jsonl or results.csv of the sweep, or its --out folder")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    rows = table(sweep_plot.read_results(args.input))
    plot(rows, args.out)
    print("| camera.distance | coverage | rows (frames/s) | squares (frames/s) | squares / rows |")
    print("|---|---|---|---|---|")
    for d, v in rows.items():
        print(f"| {d:g} | {100 * v['coverage']:.1f}% | {v['rows']:.2f} | {v['squares']:.2f} | "
              f"{v['squares'] / v['rows']:.2f} |")
    c = crossing(rows)
    if c:
        print(f"\nsquares win down to {100 * c[0]:.1f}% coverage, rows from {100 * c[1]:.1f}%")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
