#!/usr/bin/python3
"""Accuracy against the arithmetic of Wang, Lewis & Hung's Bezier pipeline: from a sweep of
bezier.arithmetic (float32, float64, fixed point of bezier.fixed_bits) with the reference check
on (`accuracy.check = true`; configs/sweeps/wang-arithmetic.toml), how often the pipeline and
the double-precision reference disagree and how far apart their hit points are.

    build/rtsim sweep configs/sweeps/wang-arithmetic.toml --out out/wang-arithmetic
    /usr/bin/python3 analysis/wang_arithmetic.py out/wang-arithmetic out/wang-arithmetic/arithmetic.png

Per primary ray, against the fixed-point width, a line per scene and view (float32 as a dashed
line of the same colour):
1. the wrong answers (missed, phantom, on another surface) as a share of the reference's hits;
2. the hit-point error p50 in patch sizes.
Prints a Markdown table of every point, with p99 in patch sizes and in pixels too.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402
import wang_accuracy  # noqa: E402

ARITHMETIC = "bezier.arithmetic"
BITS = "bezier.fixed_bits"
ACC = wang_accuracy.ACC
COLUMNS = {
    "bits": BITS,
    "both": ACC + "both",
    "missed": ACC + "missed",
    "phantom": ACC + "phantom",
    "another": ACC + "another_surface",
    "p50": ACC + "point_error.p50",
    "p99": ACC + "point_error.p99",
    "px99": ACC + "pixel_error.p99",
}


SERIES = ("scene", "view.azimuth_deg", "view.elevation_deg")


def series_name(key):
    """'builtin:teapot, azimuth 120' from a series key (scene and view settings)."""
    parts = [str(key[0])] if key[0] is not None else []
    for name, v in zip(("azimuth", "elevation"), key[1:]):
        if v is not None:
            parts.append(f"{name} {v:g}")
    return ", ".join(parts) or "the sweep"


def arithmetic_table(df):
    """{series: (floats, fixed)}, a series per scene and view (view.azimuth_deg,
    view.elevation_deg when swept): floats a dict per float arithmetic ({name: row}), fixed one
    per fixed width (sorted by bits), each row with COLUMNS' keys and wang_accuracy.add_shares's;
    InputProblem if a column is missing. A width whose pipeline hit nothing has no error
    percentiles: None there."""
    df = sweep_plot.ok_rows(df)
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    kind = common.resolve_column(df.columns, ARITHMETIC)
    cols = {k: common.resolve_column(df.columns, v) for k, v in COLUMNS.items()
            if k not in ("p50", "p99", "px99")}
    errs = {k: v for k, v in COLUMNS.items() if k in ("p50", "p99", "px99")}
    table = {}
    for _, r in df.iterrows():
        row = {k: common.to_number(r[c]) for k, c in cols.items()}
        if any(v is None for v in row.values()):
            raise common.InputProblem(f"point {r[kind]}: a value is missing (was the sweep run "
                                      "with accuracy.check = true?)")
        for k, name in errs.items():
            row[k] = common.to_number(r[name]) if name in df.columns else None
        wang_accuracy.add_shares(row)
        row["name"] = str(r[kind])
        key = (str(r["scene"]) if "scene" in df.columns else None,) + tuple(
            common.to_number(r[c]) if c in df.columns else None for c in SERIES[1:])
        floats, fixed = table.setdefault(series_name(key), ({}, []))
        if row["name"] == "fixed":
            fixed.append(row)
        else:
            floats[row["name"]] = row
    for floats, fixed in table.values():
        fixed.sort(key=lambda r: r["bits"])
    return table


def markdown(table):
    def cell(v, fmt):
        return "-" if v is None else format(v, fmt)

    lines = ["| scene, view | arithmetic | missed | phantom | another surface | wrong | "
             "error p50 | p99 (patch sizes) | p99 (pixels) |", "|" + "---|" * 9]
    for series, (floats, fixed) in table.items():
        for name, r in list(floats.items()) + [(f"fixed {r['bits']:.0f} bits", r) for r in fixed]:
            lines.append(f"| {series} | {name} | {r['missed']:.0f} | {r['phantom']:.0f} | "
                         f"{r['another']:.0f} | {100 * r['wrong']:.2f}% | "
                         f"{cell(r['p50'], '.2e')} | {cell(r['p99'], '.2e')} | "
                         f"{cell(r['px99'], '.3f')} |")
    return "\n".join(lines)


def draw(table, title):
    """(fig, (wrong, err)): the two panels against the fixed-point width, a colour a series;
    its float32 as a dashed line of its colour."""
    plt = common.pyplot()
    fig, (wrong, err) = plt.subplots(2, 1, figsize=(7.5, 8.5), sharex=True)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    ticks = set()
    for i, (series, (floats, fixed)) in enumerate(table.items()):
        color = colors[i % len(colors)]
        bits = [r["bits"] for r in fixed]
        ticks.update(bits)
        wrong.plot(bits, [max(r["wrong"], 1e-5) for r in fixed], marker="o", color=color,
                   label=series)
        pts = [(r["bits"], r["p50"]) for r in fixed if r["p50"] is not None]
        err.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", color=color,
                 label=f"{series}: p50")
        single = floats.get("float32")
        if single:
            wrong.axhline(max(single["wrong"], 1e-5), color=color, linestyle="--", linewidth=0.8)
            if single["p50"] is not None:
                err.axhline(single["p50"], color=color, linestyle="--", linewidth=0.8)
    wrong.plot([], [], color="grey", linestyle="--", linewidth=0.8, label="float32 (each series)")
    wrong.set_yscale("log")
    common.log_axis(wrong.yaxis)
    wrong.set_ylabel("wrong: missed, phantom, another surface\n(share of the reference's hits)")
    err.set_yscale("log")
    common.log_axis(err.yaxis)
    err.set_ylabel("hit-point error p50 (patch sizes)")
    err.set_xlabel("fixed-point word width, bits (bezier.fixed_bits; 8 above the point)")
    err.set_xticks(sorted(ticks))
    wrong.set_title(title, fontsize="medium")
    fig.tight_layout()
    for ax in (wrong, err):
        common.place_legend(ax, fontsize="x-small")
    return fig, (wrong, err)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="wang_arithmetic.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.jsonl or results.csv of the sweep, or its --out folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    table = arithmetic_table(sweep_plot.read_results(args.input))
    if not any(fixed for _, fixed in table.values()):
        raise common.InputProblem("the sweep has no fixed-point point (bezier.arithmetic = fixed)")
    title = args.title or "Wang's pipeline against the reference, by arithmetic"
    fig, _ = draw(table, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    print(markdown(table))
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
