#!/usr/bin/python3
"""The passes of a PixelFlow frame (`rtsim run --machine pixelflow`): when each ran and what each
cost, from stats.json (`pixelflow.passes`, docs/machines.md).

    /usr/bin/python3 analysis/pixelflow_passes.py out/run/stats.json passes.png
    /usr/bin/python3 analysis/pixelflow_passes.py out/run passes.png

Top: a timeline, one bar a pass (shadow maps, the reflection map, the camera), from its first
rasterization to its result in place (a map stored in every table memory, the camera's last
region-sample in the frame buffer); the frame's end is marked. The passes overlap where the
rasterizers run ahead (seed 004 L128). Bottom: for each pass, the busiest rasterizer's and the
busiest shader's busy time and the time the composition network carried its bytes at its rate:
the longest of them is what bounds a pass that is not bound by its table writes.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def pass_rows(stats):
    """[(name, begin_s, done_s, rasterize_busiest_s, shade_busiest_s, network_bytes)] in the
    order the machine ran them, and the frame (s); InputProblem without a pixelflow section."""
    pf = stats.get("pixelflow")
    if not isinstance(pf, dict) or not isinstance(pf.get("passes"), dict) or not pf["passes"]:
        raise common.InputProblem("stats.json has no pixelflow.passes (written by "
                                  "`rtsim run --machine pixelflow`)")
    rows = []
    for name, p in pf["passes"].items():
        if not isinstance(p, dict) or "done_s" not in p:
            raise common.InputProblem(f"pixelflow.passes.{name}: expected an object with done_s")
        rows.append((name, float(p.get("begin_s", 0.0)), float(p["done_s"]),
                     float(p.get("rasterize_busiest_s", 0.0)),
                     float(p.get("shade_busiest_s", 0.0)), float(p.get("network_bytes", 0.0))))
    return rows, float(stats.get("simulated_time_s", max(r[2] for r in rows)))


def network_rate(stats):
    """The composition network's rate in bytes/s from the run's parameters (lanes x bit rate),
    or None."""
    params = stats.get("params", {})
    try:
        lanes = float(params["composition.link.lanes"])
        value, unit = str(params["composition.link.bit_rate"]).split()
        scale = {"bit/s": 1, "kbit/s": 1e3, "Mbit/s": 1e6, "Gbit/s": 1e9}[unit]
        return lanes * float(value) * scale / 8.0
    except (KeyError, ValueError, TypeError):
        return None


def draw(rows, frame, rate, title):
    plt = common.pyplot()
    scale, unit = common.time_unit(frame)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 6))
    y = list(range(len(rows)))[::-1]
    colours = {"shadow": "tab:gray", "reflection": "tab:blue", "camera": "tab:orange"}
    for yi, (name, begin, done, *_rest) in zip(y, rows):
        colour = next((c for k, c in colours.items() if name.startswith(k)), "tab:green")
        top.barh(yi, (done - begin) * scale, left=begin * scale, color=colour)
        top.text(done * scale, yi, f"  {(done - begin) * scale:.3g} {unit}", va="center",
                 fontsize="x-small")
    top.axvline(frame * scale, color="black", linestyle="--",
                label=f"frame {frame * scale:.4g} {unit}")
    top.set_yticks(y)
    top.set_yticklabels([r[0] for r in rows], fontsize="small")
    top.set_xlabel(f"simulated time ({unit}): first rasterization to the result in place")
    top.set_xlim(0, frame * scale * 1.2)
    top.set_title(title, fontsize="medium")
    width = 0.25
    for k, (label, index, colour) in enumerate([("busiest rasterizer", 3, "tab:purple"),
                                                ("busiest shader", 4, "tab:red")]):
        bottom.barh([v + (k - 1) * width for v in y], [r[index] * scale for r in rows],
                    height=width, color=colour, label=label)
    if rate:
        bottom.barh([v + width for v in y], [r[5] / rate * scale for r in rows], height=width,
                    color="tab:cyan", label=f"network at {rate * 8 / 1e9:.3g} Gbit/s")
    bottom.set_yticks(y)
    bottom.set_yticklabels([r[0] for r in rows], fontsize="small")
    bottom.set_xlabel(f"busy time in the pass ({unit})")
    fig.tight_layout()
    for ax in (top, bottom):
        common.place_legend(ax, fontsize="x-small")
    return fig, (top, bottom)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="pixelflow_passes.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --machine pixelflow`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    rows, frame = pass_rows(stats)
    pf = stats["pixelflow"]
    title = args.title or (f"PixelFlow's passes: {pf.get('rasterizers', '?')} rasterizers, "
                           f"{pf.get('shaders', '?')} shaders, {stats.get('scene', '?')}, "
                           f"{stats.get('spp', '?')} samples a pixel")
    fig, _ = draw(rows, frame, network_rate(stats), title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
