#!/usr/bin/python3
"""Accuracy against cost for Wang, Lewis & Hung's Bezier pipeline: from a sweep of the loop
stage count (bezier.iterations) with the reference check on (`accuracy.check = true`;
configs/sweeps/wang-accuracy.toml), how often the pipeline and the double-precision reference
disagree and how far apart their hit points are, beside the latency and DSPs each stage count
costs. The throughput does not depend on the stage count (a job a pipeline cycle whatever N,
seed 002 L437): the stages cost hardware and latency.

    build/rtsim sweep configs/sweeps/wang-accuracy.toml --out out/wang-accuracy
    /usr/bin/python3 analysis/wang_accuracy.py out/wang-accuracy out/wang-accuracy/accuracy.png

Per primary ray (a pixel), top to bottom:
1. the reference's hits the pipeline missed, the pipeline's hits the reference does not have
   (phantoms: the loose hull test of the early stages), and hits on another surface (further
   than 8 final subpatch widths from the reference's point), each as a share of the reference's
   hits; their sum is "wrong";
2. the distribution of the hit-point error (p50, p90, p99) of the rays both hit on the same
   surface, in units of the patch's size (its control box diagonal), beside the final
   subpatch's width 2^-(N+1);
3. the same error in pixels of the swept image (the pixel's width at the hit);
4. the pipeline's latency and its DSP count.

Prints the same numbers as a Markdown table, and the stage count with the fewest wrong answers.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402

STAGES = "bezier.iterations"
ACC = "wang.accuracy.rays."
COLUMNS = {
    "stages": STAGES,
    "compared": ACC + "compared",
    "both": ACC + "both",
    "missed": ACC + "missed",
    "phantom": ACC + "phantom",
    "another": ACC + "another_surface",
    "p50": ACC + "point_error.p50",
    "p90": ACC + "point_error.p90",
    "p99": ACC + "point_error.p99",
    "px50": ACC + "pixel_error.p50",
    "px90": ACC + "pixel_error.p90",
    "px99": ACC + "pixel_error.p99",
    "latency_s": "wang.latency_s",
    "dsps": "wang.dsps",
    "rpi_per_s": "wang.throughput_rpi_per_s",
}


def add_shares(row):
    """Adds to a row of counts (both, missed, phantom, another) ref_hits and the shares of the
    reference's hits: missed_share, phantom_share, another_share, disagreement (missed +
    phantom) and wrong (all three)."""
    ref_hits = row["both"] + row["missed"]
    row["ref_hits"] = ref_hits
    for k in ("missed", "phantom", "another"):
        row[k + "_share"] = row[k] / ref_hits if ref_hits else 0.0
    row["disagreement"] = (row["missed"] + row["phantom"]) / ref_hits if ref_hits else 0.0
    row["wrong"] = row["disagreement"] + row["another_share"]


def accuracy_table(df):
    """One dict per stage count (sorted), with the COLUMNS' keys plus ref_hits and the shares
    missed_share, phantom_share, another_share, disagreement (missed + phantom) over the
    reference's hits; InputProblem if a column is missing."""
    df = sweep_plot.ok_rows(df)
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    cols = {k: common.resolve_column(df.columns, v) for k, v in COLUMNS.items()}
    rows = []
    for _, r in df.iterrows():
        row = {k: common.to_number(r[c]) for k, c in cols.items()}
        if any(v is None for v in row.values()):
            raise common.InputProblem(f"point with {STAGES}={r[cols['stages']]}: a value is "
                                      "missing (was the sweep run with accuracy.check = true?)")
        add_shares(row)
        row["width"] = 2.0 ** -(row["stages"] + 1)
        rows.append(row)
    rows.sort(key=lambda r: r["stages"])
    return rows


def fewest_wrong(rows):
    """The stage count with the fewest wrong answers (missed, phantom or another surface; the
    first of equals)."""
    return min(rows, key=lambda r: (r["wrong"], r["stages"]))["stages"]


def markdown(rows):
    head = ("| stages | DSPs | latency | missed | phantom | another surface | hit/miss "
            "disagreement | wrong | error p50 | p99 (patch sizes) | p50 | p99 (pixels) |")
    lines = [head, "|" + "---|" * 12]
    for r in rows:
        lines.append(
            f"| {r['stages']:.0f} | {r['dsps']:.0f} | {r['latency_s'] * 1e6:.1f} us | "
            f"{r['missed']:.0f} | {r['phantom']:.0f} | {r['another']:.0f} | "
            f"{100 * r['disagreement']:.2f}% | {100 * r['wrong']:.2f}% | {r['p50']:.2e} | "
            f"{r['p99']:.2e} | {r['px50']:.3f} | {r['px99']:.3f} |")
    return "\n".join(lines)


def draw(rows, title):
    """(fig, (top, err, pix, cost)): the four panels against the stage count."""
    plt = common.pyplot()
    n = [r["stages"] for r in rows]
    fig, (top, err, pix, cost) = plt.subplots(4, 1, figsize=(7.5, 11.5), sharex=True)
    for key, label, color in (("missed_share", "missed (reference hits, pipeline misses)",
                               "tab:red"),
                              ("phantom_share", "phantom (pipeline hits, reference misses)",
                               "tab:purple"),
                              ("another_share", "hit on another surface", "tab:orange")):
        top.plot(n, [max(r[key], 1e-5) for r in rows], marker="o", color=color, label=label)
    top.plot(n, [max(r["disagreement"], 1e-5) for r in rows], color="black", linestyle="--",
             label="hit/miss disagreement (missed + phantom)")
    top.plot(n, [max(r["wrong"], 1e-5) for r in rows], color="black", linewidth=2,
             label="wrong (all three)")
    best = fewest_wrong(rows)
    for ax in (top, err, pix, cost):
        ax.axvline(best, color="grey", linestyle=":")
        ax.axvline(10, color="tab:green", linestyle="--")
    top.plot([], [], color="grey", linestyle=":", label=f"fewest wrong: {best:.0f} stages")
    top.plot([], [], color="tab:green", linestyle="--", label="the paper's 10 stages (L286)")
    top.set_yscale("log")
    common.log_axis(top.yaxis)
    top.set_ylim(1e-4, 5)
    top.set_ylabel("share of the reference's hits")
    for key, style in (("p50", "-"), ("p90", "--"), ("p99", ":")):
        err.plot(n, [r[key] for r in rows], marker="o", linestyle=style, color="tab:blue",
                 label=f"hit-point error {key}")
    err.plot(n, [r["width"] for r in rows], color="grey", label="final subpatch width 2^-(N+1)")
    err.set_yscale("log")
    common.log_axis(err.yaxis)
    err.set_ylabel("patch sizes")
    for key, style in (("px50", "-"), ("px90", "--"), ("px99", ":")):
        pix.plot(n, [r[key] for r in rows], marker="o", linestyle=style, color="tab:cyan",
                 label=f"hit-point error p{key[2:]}")
    pix.axhline(0.5, color="grey", linewidth=0.8, label="half a pixel")
    pix.set_yscale("log")
    common.log_axis(pix.yaxis)
    pix.set_ylabel("pixels (this image)")
    scale, unit = common.time_unit(max(r["latency_s"] for r in rows))
    cost.plot(n, [r["latency_s"] * scale for r in rows], marker="o", color="tab:brown",
              label="pipeline latency")
    cost.set_ylabel(f"latency ({unit})")
    dsp = cost.twinx()
    dsp.plot(n, [r["dsps"] for r in rows], marker="s", markerfacecolor="none", linestyle="--",
             color="tab:gray", label="DSPs")
    dsp.set_ylabel("DSPs")
    common.integer_axis(dsp.yaxis)
    cost.set_xlabel("loop stages N (bezier.iterations); throughput is one job a cycle for any N")
    cost.set_xticks(n)
    top.set_title(title, fontsize="medium")
    fig.tight_layout()
    common.place_legend(top, fontsize="x-small", ncol=2)
    for ax in (err, pix):
        common.place_legend(ax, fontsize="x-small")
    lines, labels = cost.get_legend_handles_labels()
    more, more_labels = dsp.get_legend_handles_labels()
    # On the twin axes, drawn after cost: no line is drawn over the legend.
    common.place_legend(dsp, handles=lines + more, labels=labels + more_labels,
                        fontsize="x-small")
    return fig, (top, err, pix, cost)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="wang_accuracy.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.jsonl or results.csv of the sweep, or its --out folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    rows = accuracy_table(sweep_plot.read_results(args.input))
    compared = rows[0]["compared"]
    title = args.title or (f"Wang's pipeline against the reference: {compared:.0f} primary rays, "
                           f"{rows[0]['ref_hits']:.0f} reference hits")
    fig, _ = draw(rows, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    print(markdown(rows))
    print(f"\nfewest wrong answers at {fewest_wrong(rows):.0f} stages")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
