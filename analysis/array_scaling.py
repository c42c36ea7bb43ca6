#!/usr/bin/python3
"""Ullner's ray-tracing array against its size (configs/sweeps/array-scaling.toml): the frame time
and the speed-up over each line's smallest array, against the processors, one colour a scene,
solid for the fixed subdivision (array.subvolumes = the largest array's side at every size) and
dashed for the default that grows with the array (array.subvolumes = 0: the array's side). The
grey line is a speed-up equal to the processors' ratio.

    build/rtsim sweep configs/sweeps/array-scaling.toml --out out/array-scaling
    /usr/bin/python3 analysis/array_scaling.py out/array-scaling docs/array-scaling.png

Prints a Markdown table: per scene and subdivision, the frame time at each size, the speed-up
over the smallest size, and the processors' mean and busiest CPU utilisation (the class
node*, module_classes in stats.json).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402


def lines(df):
    """{(scene, subdivision): [(processors, frame_s, mean_busy, max_busy)], sorted}; subdivision
    is "grows" or the fixed count."""
    df = sweep_plot.ok_rows(df)
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    rows_c = common.resolve_column(df.columns, "array.rows")
    cols_c = common.resolve_column(df.columns, "array.cols")
    sub_c = common.resolve_column(df.columns, "array.subvolumes")
    time_c = common.resolve_column(df.columns, "simulated_time_s")
    mean_c = common.resolve_column(df.columns, "module_classes.node*.utilization.mean")
    max_c = common.resolve_column(df.columns, "module_classes.node*.utilization.max")
    out = {}
    for _, r in df.iterrows():
        n = int(common.to_number(r[rows_c]) * common.to_number(r[cols_c]))
        sub = int(common.to_number(r[sub_c]))
        key = (str(r["scene"]), "grows" if sub == 0 else str(sub))
        out.setdefault(key, []).append((n, common.to_number(r[time_c]), common.to_number(r[mean_c]),
                                        common.to_number(r[max_c])))
    return {k: sorted(v) for k, v in sorted(out.items())}


def label(scene, sub):
    name = scene.removeprefix("builtin:")
    return f"{name}, " + ("subdivision grows with the array" if sub == "grows"
                         else f"fixed {sub}³ subvolumes")


def plot(data, out_path):
    plt = common.pyplot()
    fig, (ax_t, ax_s) = plt.subplots(1, 2, figsize=(12, 4.8))
    scenes = sorted({s for s, _ in data})
    colours = {s: f"C{i}" for i, s in enumerate(scenes)}
    procs = sorted({p for v in data.values() for p, *_ in v})
    scale, unit = common.time_unit(max(t for v in data.values() for _, t, *_ in v))
    for (scene, sub), pts in data.items():
        style = dict(color=colours[scene], linestyle="--" if sub == "grows" else "-",
                     marker="o" if sub == "grows" else "s", label=label(scene, sub))
        ax_t.plot([p for p, *_ in pts], [t * scale for _, t, *_ in pts], **style)
        ax_s.plot([p for p, *_ in pts], [pts[0][1] / t for _, t, *_ in pts], **style)
    ax_s.plot(procs, [p / procs[0] for p in procs], color="grey", linewidth=1,
              label="speed-up = processors / " + str(procs[0]))
    for ax in (ax_t, ax_s):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(procs)
        ax.set_xticklabels([str(p) for p in procs])
        ax.minorticks_off()
        common.log_axis(ax.yaxis)
        ax.set_xlabel("processors (2x2 to 32x32)")
        ax.grid(True, which="both", alpha=0.3)
    ax_t.set_ylabel(f"frame time ({unit})")
    ax_s.set_ylabel(f"speed-up over {procs[0]} processors")
    ax_t.set_title("ullner-array: frame time", fontsize="small")
    ax_s.set_title("speed-up (solid: fixed subdivision; dashed: grows with the array)",
                   fontsize="small")
    fig.tight_layout()
    common.place_legend(ax_s, fontsize="x-small")
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="array_scaling.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.jsonl or results.csv of the sweep, or its --out folder")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    data = lines(sweep_plot.read_results(args.input))
    plot(data, args.out)
    procs = sorted({p for v in data.values() for p, *_ in v})
    print("| scene | subdivision | " + " | ".join(str(p) for p in procs) + " |")
    print("|---|---|" + "---|" * len(procs))
    for (scene, sub), pts in data.items():
        cells = {p: f"{t * 1e3:.4g} ms, {pts[0][1] / t:.3g}x, {100 * m:.0f}/{100 * b:.0f}%"
                 for p, t, m, b in pts}
        print(f"| {scene} | {sub} | " + " | ".join(cells.get(p, "") for p in procs) + " |")
    print("\n(frame time, speed-up over the smallest array, mean/busiest processor CPU busy)")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
