#!/usr/bin/python3
"""Run time against error for every machine, from bench/pareto.py's pareto.json: one panel per
machine, the speed-up of each setting over the reference (quantum 0, the whole frame in detail)
against its frame-time error, each scene in its own colour: quantum settings as squares, sampled
runs with the image as circles, timing-only sampled runs (--image none) as triangles with the
work-weighted estimate and as diamonds with the systematic one (hollow when the 99.7% interval
misses the reference). The grey box is the target: at least 10x faster with at most 1% error.

    /usr/bin/python3 analysis/pareto_plot.py out/pareto/pareto.json docs/pareto.png
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def main(argv):
    ap = argparse.ArgumentParser(prog="pareto_plot.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="pareto.json of bench/pareto.py")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    rows = common.read_json(args.input)
    if not isinstance(rows, list) or not rows:
        raise common.InputProblem(f"{args.input}: no runs")
    machines = list(dict.fromkeys(r["machine"] for r in rows))
    plt = common.pyplot()
    cols = 4
    nrows = (len(machines) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.6 * nrows), squeeze=False)
    floor = 1e-5  # errors of 0 are drawn here
    ceiling = 1.0  # and errors over 100% here
    for ax, machine in zip(axes.flat, machines):
        mine = [r for r in rows if r["machine"] == machine and r["setting"] != "reference"]
        scenes = list(dict.fromkeys(r["scene"] for r in rows if r["machine"] == machine))
        ax.add_patch(plt.Rectangle((floor, 10), 0.01 - floor, 1e4, color="0.9", zorder=0))
        for i, scene in enumerate(scenes):
            color = f"C{i}"
            for r in (x for x in mine if x["scene"] == scene):
                setting = r["setting"]
                sampled = "sample" in setting or "systematic" in setting
                hollow = sampled and r.get("ci_holds") is False
                marker = ("s" if not sampled else "D" if "systematic" in setting
                          else "^" if setting.startswith("timing") else "o")
                error = r.get("error", 0)
                # Errors past the right edge are drawn on it, with their value in the label.
                x = min(max(error, floor), ceiling)
                if setting.startswith("sample-error"):
                    label = f"E=1%,K={r.get('chosen_k', '?')}"
                else:
                    label = (setting.replace("timing systematic ", "K=").replace("timing sample ", "K=")
                             .replace("sample ", "K=").replace("quantum ", "q="))
                if error > ceiling:
                    label += f" ({100 * error:.0f}%)"
                ax.scatter(x, r.get("speedup", 1), marker=marker, s=28,
                           facecolors="none" if hollow else color, edgecolors=color, zorder=2)
                ax.annotate(label, (x, r.get("speedup", 1)), textcoords="offset points",
                            xytext=(3, 2), fontsize=6, color="0.4")
            ax.scatter([], [], color=color, label=scene.replace("builtin:", ""))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(floor * 0.7, 3)
        ax.set_ylim(0.3, 100)
        ax.set_xticks([1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1])
        ax.set_xticklabels(["0", "0.01%", "0.1%", "1%", "10%", ">= 100%"], fontsize=7)
        ax.set_yticks([0.5, 1, 2, 5, 10, 20, 50])
        ax.set_yticklabels(["0.5x", "1x", "2x", "5x", "10x", "20x", "50x"], fontsize=7)
        ax.set_title(machine, fontsize="small")
        ax.set_xlabel("frame-time error", fontsize=7)
        ax.set_ylabel("speed-up over quantum 0", fontsize=7)
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(machines):]:
        ax.axis("off")
    fig.suptitle("Run time against error: squares quantum; --sample K: circles with the image, "
                 "triangles timing-only by work, diamonds timing-only systematic (hollow: interval "
                 "misses); grey: 10x at <= 1%", fontsize="small")
    fig.tight_layout()
    for ax in list(axes.flat)[:len(machines)]:
        common.place_legend(ax, fontsize=6)
    fig.tight_layout()  # room for legends that went beside their panel
    common.save(fig, args.out)
    plt.close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
