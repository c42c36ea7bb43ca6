#!/usr/bin/python3
"""Ullner's scan-line tree split n levels against scene complexity
(configs/sweeps/scanline-split.toml): the share of scan lines that miss the beam and the
scan-out's time in frames, against the segments a line the scene needs, one line a split level
n (2^n roots, L1594's 10 x 2^n segments a line). A point that failed (a splitting processor's
queue too short for a line, exit status 2) is left out and listed.

    build/rtsim sweep configs/sweeps/scanline-split.toml --jobs 2 --out out/scanline-split
    /usr/bin/python3 analysis/scanline_split.py out/scanline-split docs/scanline-split.png

Prints a Markdown table: per scene (its segments a line) and split level, the late lines and the
scan-out in frames.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402


def points(df):
    """{levels: [(segments a line, late share, frames)], sorted}, and the failed points' labels."""
    levels_c = common.resolve_column(df.columns, "tree.split_levels")
    failed = [f"{r['scene']} n = {int(common.to_number(r[levels_c]))}"
              for _, r in df.iterrows() if r.name not in sweep_plot.ok_rows(df).index]
    ok = sweep_plot.ok_rows(df)
    if ok.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    seg_c = common.resolve_column(ok.columns, "scanline_tree.scan_out.segments_a_line_mean")

    def need(r):
        # builtin:ullner-mosaic-N needs 2N; another scene, what its strips were sent.
        name = str(r["scene"])
        if name.startswith("builtin:ullner-mosaic-"):
            return 2.0 * common.to_number(name.rsplit("-", 1)[1])
        return common.to_number(r[seg_c])
    late_c = common.resolve_column(ok.columns, "scanline_tree.scan_out.late_lines")
    time_c = common.resolve_column(ok.columns, "scanline_tree.scan_out.time_s")
    line_c = common.resolve_column(ok.columns, "scanline_tree.scan_out.line_time_s")
    lines_c = common.resolve_column(ok.columns, "height")
    out = {}
    for _, r in ok.iterrows():
        lines = common.to_number(r[lines_c])
        frame = common.to_number(r[line_c]) * lines
        out.setdefault(int(common.to_number(r[levels_c])), []).append(
            (need(r), common.to_number(r[late_c]) / lines,
             common.to_number(r[time_c]) / frame))
    return {k: sorted(v) for k, v in sorted(out.items())}, failed


def plot(data, out_path):
    plt = common.pyplot()
    fig, (ax_l, ax_f) = plt.subplots(1, 2, figsize=(12, 4.8))
    for n, pts in data.items():
        style = dict(color=f"C{n}", marker="o", label=f"n = {n} ({1 << n} roots)")
        ax_l.plot([s for s, *_ in pts], [100 * late for _, late, _ in pts], **style)
        ax_f.plot([s for s, *_ in pts], [f for *_, f in pts], **style)
        # L1594: about 10 x 2^n segments a line.
        ax_l.axvline(10 * (1 << n), color=f"C{n}", linewidth=0.8, linestyle=":")
    ax_f.axhline(1.0, color="grey", linewidth=1, label="one frame (the beam's pace)")
    for ax in (ax_l, ax_f):
        ax.set_xscale("log", base=2)
        common.log_axis(ax.xaxis, integer=True)
        ax.set_xlabel("segments a line the scene needs (builtin:ullner-mosaic-N: 2N)")
        ax.grid(True, which="both", alpha=0.3)
    ax_f.set_yscale("log")
    common.log_axis(ax_f.yaxis)
    ax_l.set_ylabel("late lines (%)")
    ax_f.set_ylabel("scan-out (frames)")
    ax_l.set_title("lines that miss the beam (dotted: L1594's 10 x 2^n a line)", fontsize="small")
    ax_f.set_title("scan-out against the frame", fontsize="small")
    fig.tight_layout()
    common.place_legend(ax_f, fontsize="x-small")
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="scanline_split.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.jsonl or results.csv of the sweep, or its --out folder")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    data, failed = points(sweep_plot.read_results(args.input))
    plot(data, args.out)
    segments = sorted({round(s) for v in data.values() for s, *_ in v})
    print("| n | " + " | ".join(f"{s} a line" for s in segments) + " |")
    print("|---|" + "---|" * len(segments))
    for n, pts in data.items():
        cells = {round(s): f"{100 * late:.0f}%, {f:.2f}" for s, late, f in pts}
        print(f"| {n} | " + " | ".join(cells.get(s, "failed") for s in segments) + " |")
    print("\n(late lines, scan-out in frames)")
    if failed:
        print("failed: " + ", ".join(failed))
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
