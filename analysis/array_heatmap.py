#!/usr/bin/python3
"""Load balance of Ullner's ray-tracing array (`rtsim run --machine ullner-array`): a heat map
of each processor's busy fraction, and the traffic on every link, from stats.json.

    /usr/bin/python3 analysis/array_heatmap.py out/run/stats.json array.png
    /usr/bin/python3 analysis/array_heatmap.py out/run array.png

Left: each processor's limiting resource, one cell per processor laid out as the array (row 0
at the top: the processor holding the top of the frame buffer, L781): the busiest of its CPU
(`nodeK`), its intersection pipeline (`nodeK.pipeline`) and its memory (`nodeK.memory`),
coloured by that utilisation and lettered C, P or M (stats.json `modules`; without them,
`array.node_busy_fraction`, the CPU's). Right: each output link `nodeK.link_D` (D = n, e, s, w)
as a bar from its processor toward the neighbour, coloured by its utilisation (its colour bar
beside it); wrap links (skew and torus mappings) leave the edge. An
eye to the side under the straight mapping piles the vision rays onto one edge (seed 000 L862,
Fig. 2-30); the skewed torus spreads them (Fig. 2-32).
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

LINK = re.compile(r"^node(\d+)\.link_([nesw])$")
STEP = {"n": (0, -1), "e": (1, 0), "s": (0, 1), "w": (-1, 0)}  # (dx, dy) on the picture


def array_series(stats):
    """(busy rows x cols, [(row, col, dir, utilisation)], description); InputProblem without
    the array's keys."""
    a = stats.get("array")
    if not isinstance(a, dict) or not isinstance(a.get("node_busy_fraction"), list):
        raise common.InputProblem("stats.json has no array.node_busy_fraction (written by "
                                  "`rtsim run --machine ullner-array`)")
    busy = [[float(x) for x in row] for row in a["node_busy_fraction"]]
    cols = len(busy[0]) if busy else 0
    if not busy or any(len(r) != cols for r in busy) or cols == 0:
        raise common.InputProblem("array.node_busy_fraction: expected equal, non-empty rows")
    links = []
    modules = stats.get("modules") or {}
    # The limiting resource of each processor: the busiest of its CPU, pipeline and memory.
    limit = [["C"] * cols for _ in busy]
    for k in range(len(busy) * cols):
        r, c = divmod(k, cols)
        for suffix, letter in (("", "C"), (".pipeline", "P"), (".memory", "M")):
            m = modules.get(f"node{k}{suffix}")
            if isinstance(m, dict) and common.finite(m.get("utilization")):
                u = float(m["utilization"])
                if suffix == "" or u > busy[r][c]:
                    busy[r][c], limit[r][c] = u, letter
    for name, m in modules.items():
        g = LINK.match(name)
        if g and isinstance(m, dict) and common.finite(m.get("utilization")):
            k = int(g.group(1))
            links.append((k // cols, k % cols, g.group(2), float(m["utilization"])))
    desc = (f"{len(busy)} x {cols}, {a.get('mapping', '?')} mapping, depth axis "
            f"{a.get('depth_axis', '?')}, {a.get('subvolumes', '?')} subvolumes per axis")
    return busy, limit, links, desc


RESOURCE = {"C": "CPU", "P": "pipeline", "M": "memory"}


def plot(busy, limit, links, desc, title, out_path):
    import numpy as np

    plt = common.pyplot()
    rows, cols = len(busy), len(busy[0])
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5))
    b = np.asarray(busy)
    im = left.imshow(b, cmap="viridis", vmin=0.0, vmax=max(1e-9, float(b.max())),
                     interpolation="nearest")
    fig.colorbar(im, ax=left, fraction=0.046, label="busy fraction of the limiting resource")
    if rows * cols <= 256:  # a letter a cell while they stay legible
        for r in range(rows):
            for c in range(cols):
                left.text(c, r, limit[r][c], ha="center", va="center",
                          fontsize=10 if rows * cols <= 64 else 6,
                          color="white" if b[r][c] < 0.6 * b.max() else "black")
    counts = {}
    for row in limit:
        for x in row:
            counts[x] = counts.get(x, 0) + 1
    limits = ", ".join(f"{RESOURCE[x]} {n}" for x, n in sorted(counts.items(), key=lambda i: -i[1]))
    mean = float(b.mean())
    left.set_title(f"limiting resource ({limits}): max {b.max():.3f}, mean {mean:.3f}, "
                   f"max/mean {b.max() / mean if mean > 0 else 0:.2f}", fontsize="small")
    left.set_xlabel("column")
    left.set_ylabel("row")
    right.imshow(b, cmap="Greys", vmin=0.0, vmax=max(1e-9, float(b.max())) * 3,
                 interpolation="nearest")
    top = max([u for *_, u in links] + [1e-9])
    # inferno_r without its palest sixth, which would vanish on the grey cells; the bar beside
    # the panel is the same map.
    from matplotlib.colors import ListedColormap
    cmap = ListedColormap(plt.get_cmap("inferno_r")(np.linspace(0.15, 1.0, 256)))
    for row, col, d, u in links:
        dx, dy = STEP[d]
        right.plot([col + 0.12 * dx - 0.08 * dy, col + 0.5 * dx - 0.08 * dy],
                   [row + 0.12 * dy + 0.08 * dx, row + 0.5 * dy + 0.08 * dx],
                   color=cmap(u / top), linewidth=1 + 4 * u / top,
                   solid_capstyle="butt")
    bar = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0.0, top))
    bar.set_array([])
    fig.colorbar(bar, ax=right, fraction=0.046, label="link utilisation")
    right.set_xlim(-0.6, cols - 0.4)
    right.set_ylim(rows - 0.4, -0.6)
    right.set_title(f"links (outgoing, toward the neighbour): max utilisation {top:.3f}",
                    fontsize="medium")
    right.set_xlabel("column")
    for ax in (left, right):
        common.integer_axis(ax.xaxis)
        common.integer_axis(ax.yaxis)
    fig.suptitle(f"{title}\n{desc}", fontsize="medium")
    fig.tight_layout()  # the two-line suptitle clear of the panels' titles
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="array_heatmap.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine ullner-array`, or its "
                                  "folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    busy, limit, links, desc = array_series(stats)
    title = args.title or f"Load balance: {stats.get('scene', '?')}"
    plot(busy, limit, links, desc, title, args.out)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
