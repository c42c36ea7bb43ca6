#!/usr/bin/python3
"""Ullner's hidden-line pipeline against the scene's size (configs/sweeps/hidden-line-polygons.toml;
seed 000 L1914): the frame time (every segment in, the stream through to the divider) and a
segment's delay through the pipe, first and mean, against the polygons in front of the eye, with
the seed's estimate (one 8 us message time a plane processor: 40 us a four-sided polygon) and a
thirtieth of a second marked (left); the links' utilisation along the pipe, first processor to
last, for each scene (right). Every figure is read from each point's stats.json (hidden_line).

    build/rtsim sweep configs/sweeps/hidden-line-polygons.toml --jobs 2 --out out/hidden-line-polygons
    /usr/bin/python3 analysis/hidden_line_polygons.py out/hidden-line-polygons docs/hidden-line-polygons.png

Prints a Markdown table: polygons, plane processors, frame, first and mean delay (ms).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402
import sweep_plot  # noqa: E402

# The seed's estimate (L1914): one message time, 8 us, a plane processor.
MESSAGE_S = 8e-6
FRAME_S = 1.0 / 30.0


def points(folder):
    """[(polygons, plane processors, frame s, first s, mean s, [link utilisation by bin])], by
    polygons, from the sweep's folder."""
    df = sweep_plot.ok_rows(sweep_plot.read_results(folder))
    if df.empty:
        raise common.InputProblem("no successful points in the sweep's results")
    out = []
    for _, r in df.iterrows():
        _, stats = common.read_stats(os.path.join(folder, str(r["dir"])))
        hl = stats.get("hidden_line")
        if not isinstance(hl, dict) or "segment_latency_s" not in hl:
            raise common.InputProblem(f"{r['dir']}: no hidden_line.segment_latency_s in its "
                                      "stats.json")
        lat = hl["segment_latency_s"]
        out.append((hl["polygons"], hl["plane_processors"], hl["frame_time_s"], lat["first"],
                    lat["mean"], [b["link_utilization"] for b in hl.get("along_pipe", [])]))
    return sorted(out)


def plot(data, out_path):
    plt = common.pyplot()
    fig, (ax_t, ax_u) = plt.subplots(1, 2, figsize=(12, 4.8))
    polys = [p[0] for p in data]
    ax_t.plot(polys, [p[2] * 1e3 for p in data], "o-", color="C0", label="frame time")
    ax_t.plot(polys, [p[4] * 1e3 for p in data], "s-", color="C1",
              label="a segment's delay, mean")
    ax_t.plot(polys, [p[3] * 1e3 for p in data], "^--", color="C1", alpha=0.6,
              label="the first segment's delay")
    ax_t.plot(polys, [p[1] * MESSAGE_S * 1e3 for p in data], ":", color="k",
              label="seed: 8 us a plane processor (L1914)")
    ax_t.axhline(FRAME_S * 1e3, color="C3", linewidth=0.8,
                 label="a thirtieth of a second")
    ax_t.set_xlabel("polygons in front of the eye (random squares)")
    ax_t.set_ylabel("time (ms)")
    ax_t.set_title("frame and segment delay against the scene", fontsize="small")
    ax_t.grid(True, alpha=0.3)
    common.place_legend(ax_t, fontsize="x-small")
    for i, p in enumerate(data):
        util = p[5]
        if not util:
            continue
        xs = [(k + 0.5) / len(util) for k in range(len(util))]
        ax_u.plot(xs, [u * 100 for u in util], color=f"C{i % 10}",
                  label=f"{common.plain_number(p[0])} polygons")
    ax_u.set_xlabel("position along the pipe (first processor 0, last 1)")
    ax_u.set_ylabel("link utilisation (%)")
    ax_u.set_ylim(bottom=0)
    ax_u.set_title("utilisation along the pipe (L1914: delays close the gaps)", fontsize="small")
    ax_u.grid(True, alpha=0.3)
    fig.tight_layout()
    common.place_legend(ax_u, fontsize="x-small")
    common.save(fig, out_path)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="hidden_line_polygons.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="the sweep's --out folder (results and points/)")
    ap.add_argument("out", help="PNG to write")
    args = ap.parse_args(argv)
    if not os.path.isdir(args.input):
        raise common.InputProblem(f"{args.input}: expected the sweep's --out folder")
    data = points(args.input)
    plot(data, args.out)
    print("| polygons | plane processors | frame (ms) | first segment (ms) | mean segment (ms) |"
          " seed's estimate (ms) |")
    print("|---|---|---|---|---|---|")
    for polys, planes, frame, first, mean, _ in data:
        print(f"| {polys} | {planes} | {frame * 1e3:.1f} | {first * 1e3:.1f} | {mean * 1e3:.1f} |"
              f" {planes * MESSAGE_S * 1e3:.1f} |")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
