#!/usr/bin/python3
"""Where a ray spends its time: the per-stage breakdown recorded by `rtsim run --latency-probe`
(stats.json `latency_probe`, docs/stats.md).

    /usr/bin/python3 analysis/latency_breakdown.py out/run/stats.json breakdown.png
    /usr/bin/python3 analysis/latency_breakdown.py out/run breakdown.png --title "grid 11"

One horizontal bar per stage (a module or queue, in the order a ray meets them), stacked from
its mean queueing, service and transfer time per ray; below them the unattributed rest (the
end-to-end latency the stages do not cover; 0 when the machine reports every wait and every
piece of work) and, as the last bar, the end-to-end mean. Per-stage values are means over all
probed rays, a ray that never met a stage counting 0 there, so the stage bars plus the
unattributed bar add up to the end-to-end bar.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

PARTS = ("queueing", "service", "transfer")
COLORS = {"queueing": "tab:orange", "service": "tab:blue", "transfer": "tab:green",
          "unattributed": "tab:gray", "end to end": "black"}
UNATTRIBUTED = "unattributed"
END_TO_END = "end to end (mean)"


def breakdown_series(stats):
    """{"stages": [name, ...], "queueing": [s, ...], "service": [...], "transfer": [...],
    "end_to_end_s": mean, "unattributed_s": rest, "rays": n, "p99_s": [...]} from stats.json;
    InputProblem if it has no latency_probe (a run without --latency-probe)."""
    probe = stats.get("latency_probe")
    if not isinstance(probe, dict):
        raise common.InputProblem("stats.json has no latency_probe (written by "
                                  "`rtsim run --latency-probe`)")
    stages = probe.get("stages")
    e2e = probe.get("end_to_end_s")
    if not isinstance(stages, dict) or not isinstance(e2e, dict):
        raise common.InputProblem("latency_probe: expected objects 'stages' and 'end_to_end_s'")
    out = {"stages": [], "p99_s": [], "rays": int(probe.get("rays", 0))}
    for part in PARTS:
        out[part] = []
    for name, st in stages.items():
        if not isinstance(st, dict):
            raise common.InputProblem(f"latency_probe.stages.{name}: expected an object")
        out["stages"].append(name)
        for part in PARTS:
            v = st.get(f"{part}_s", 0.0)
            if not common.finite(v):
                raise common.InputProblem(f"latency_probe.stages.{name}.{part}_s: expected a "
                                          f"number, got {v!r}")
            out[part].append(float(v))
        out["p99_s"].append(float(st["p99_s"]) if common.finite(st.get("p99_s")) else None)
    for key, src in (("end_to_end_s", e2e.get("mean")),
                     ("unattributed_s", probe.get("unattributed_s", 0.0))):
        if not common.finite(src):
            raise common.InputProblem(f"latency_probe: {key} is not a number ({src!r})")
        out[key] = float(src)
    return out


def draw(series, title):
    """(fig, ax, bars): the figure, and bars = {row label: {part: (left, width)}} in the plot's
    time unit as drawn (rows: each stage, then unattributed, then end to end)."""
    import numpy as np

    plt = common.pyplot()
    labels = series["stages"] + [UNATTRIBUTED, END_TO_END]
    n = len(labels)
    fig, ax = plt.subplots(figsize=(8, 1.2 + 0.45 * n))
    widest = max([series["end_to_end_s"], abs(series["unattributed_s"])] +
                 [sum(series[p][i] for p in PARTS) for i in range(len(series["stages"]))])
    scale, unit = common.time_unit(widest if widest > 0 else 1.0)
    y = np.arange(n)
    bars = {label: {} for label in labels}
    left = np.zeros(len(series["stages"]))
    for part in PARTS:
        w = np.asarray(series[part]) * scale
        ax.barh(y[:len(w)], w, left=left, color=COLORS[part], label=part, height=0.6)
        for i, name in enumerate(series["stages"]):
            bars[name][part] = (float(left[i]), float(w[i]))
        left = left + w
    rest = series["unattributed_s"] * scale
    ax.barh([y[-2]], [rest], color=COLORS["unattributed"], height=0.6, label=UNATTRIBUTED)
    bars[UNATTRIBUTED]["unattributed"] = (0.0, float(rest))
    total = series["end_to_end_s"] * scale
    ax.barh([y[-1]], [total], color=COLORS["end to end"], height=0.6, alpha=0.8)
    bars[END_TO_END]["end to end"] = (0.0, float(total))
    for i, label in enumerate(labels):
        width = sum(w for _, w in bars[label].values())
        share = width / total if total > 0 else 0.0
        if label == UNATTRIBUTED and abs(share) < 1e-9:
            # Rounding only: say so rather than print a meaningless 1e-15.
            text = " ~0 (rounding)"
        elif label == END_TO_END:
            text = " " + common.seconds_text(width / scale)
        else:
            text = f" {common.seconds_text(width / scale)} ({100 * share:.3g}%)"
        ax.text(max(width, 0.0), i, text, va="center", fontsize="small")
    ax.set_yticks(y)
    ax.set_yticklabels(labels)
    ax.invert_yaxis()  # the first stage a ray meets at the top
    ax.set_xlabel(f"mean time per ray ({unit})")
    ax.set_xlim(0, max(total, max(left, default=0.0), rest, 1e-30) * 1.25)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(True, axis="x", alpha=0.3)
    ax.set_title(title)
    return fig, ax, bars


def main(argv):
    ap = argparse.ArgumentParser(
        prog="latency_breakdown.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="stats.json of `rtsim run --latency-probe`, or its folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    _, stats = common.read_stats(args.input)
    series = breakdown_series(stats)
    title = args.title or (f"Where a ray spends its time: {stats.get('machine', '?')} on "
                           f"{stats.get('scene', '?')} ({series['rays']} rays)")
    fig, _, _ = draw(series, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
