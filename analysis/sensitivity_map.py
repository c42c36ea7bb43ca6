#!/usr/bin/python3
"""Which validation figures move with which assumptions (`rtsim validate --sensitivity`): a map
of figures (rows) against assumptions (columns) from validation-sensitivity.json.

    /usr/bin/python3 analysis/sensitivity_map.py validation-sensitivity.json sensitivity.png

Each cell is the figure's relative change under the move of that assumption that changed it
most (x0.5, x2, or a stated value), blue for a fall and red for a rise, clipped at +-50%; the
number in the cell is that change in percent. A cell framed in black is a move under which the
figure's verdict changes (a pass becomes a fail, or the reverse). Blank: the figure does not
name that assumption.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

CLIP = 0.5  # the colour scale's ends: +-50%


def cells(doc):
    """(figure ids, params, {(figure, param): (change, flips)}) from the document."""
    if not isinstance(doc, dict):
        raise common.InputProblem("expected a JSON object (validation-sensitivity.json)")
    entries = doc.get("entries")
    if not isinstance(entries, list):
        raise common.InputProblem("no \"entries\" list: expected the validation-sensitivity.json "
                                  "that `rtsim validate --sensitivity` writes")
    figures, params, out = [], [], {}
    for e in entries:
        f, p = e.get("figure"), e.get("param")
        if not isinstance(f, str) or not isinstance(p, str):
            raise common.InputProblem("an entry without \"figure\" or \"param\"")
        if f not in figures:
            figures.append(f)
        if p not in params:
            params.append(p)
        change = e.get("relative_change")
        change = float(change) if common.finite(change) else float("nan")
        flips = bool(e.get("flips"))
        old = out.get((f, p))
        if old is None:
            out[(f, p)] = (change, flips)
        else:
            worst = old[0]
            if math.isnan(worst) or (not math.isnan(change) and abs(change) > abs(worst)):
                worst = change
            out[(f, p)] = (worst, old[1] or flips)
    return figures, params, out


def draw(doc, out_path):
    figures, params, values = cells(doc)
    if not figures:
        raise common.InputProblem("no figure names an assumption: nothing to draw")
    plt = common.pyplot()
    import numpy as np
    from matplotlib.patches import Rectangle

    grid = np.full((len(figures), len(params)), np.nan)
    for (f, p), (change, _) in values.items():
        grid[figures.index(f), params.index(p)] = change
    width = max(6.0, 1.0 + 0.45 * len(params))
    height = max(4.0, 1.5 + 0.28 * len(figures))
    fig, ax = plt.subplots(figsize=(width, height))
    cmap = plt.get_cmap("RdBu_r").copy()
    cmap.set_bad("white")
    image = ax.imshow(np.ma.masked_invalid(np.clip(grid, -CLIP, CLIP)), cmap=cmap, vmin=-CLIP,
                      vmax=CLIP, aspect="auto")
    for (f, p), (change, flips) in values.items():
        y, x = figures.index(f), params.index(p)
        if not math.isnan(change):
            ax.text(x, y, "%+.0f" % (100 * change), ha="center", va="center", fontsize=6,
                    color="white" if abs(change) > 0.6 * CLIP else "black")
        else:
            ax.text(x, y, "n/a", ha="center", va="center", fontsize=6)
        if flips:
            ax.add_patch(Rectangle((x - 0.5, y - 0.5), 1, 1, fill=False, edgecolor="black",
                                   linewidth=1.6))
    ax.set_xticks(range(len(params)))
    ax.set_xticklabels(params, rotation=60, ha="right", fontsize=7)
    ax.set_yticks(range(len(figures)))
    ax.set_yticklabels(figures, fontsize=7)
    ax.set_xlabel("assumption (framed: the figure's verdict changes)")
    ax.set_ylabel("figure")
    bar = fig.colorbar(image, ax=ax, fraction=0.04, pad=0.02)
    bar.set_label("relative change of the figure (largest move; clipped at +-50%)")
    bar.set_ticks([-0.5, -0.25, 0, 0.25, 0.5])
    bar.set_ticklabels(["-50%", "-25%", "0", "+25%", "+50%"])
    ax.set_title("rtsim validate --sensitivity (%s)" % doc.get("mode", "?"))
    fig.tight_layout()
    common.save(fig, out_path)


def main(argv):
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="validation-sensitivity.json")
    ap.add_argument("output", help="the PNG to write")
    args = ap.parse_args(argv)
    draw(common.read_json(args.input), args.output)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
