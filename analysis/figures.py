#!/usr/bin/python3
"""The seeds' figures redrawn with the simulated values over the seeds' own numbers, from the
folder `rtsim validate --out DIR` writes (validation.json, fig2-18.csv; with --keep also the
run folders runs-XXXXXX/KEY/stats.json, which add curves the table has no room for).

    rtsim validate --quick --out val --keep
    /usr/bin/python3 analysis/figures.py val figures.png                 # every figure it can draw
    /usr/bin/python3 analysis/figures.py val fig2-18.png --figure fig2-18
    /usr/bin/python3 analysis/figures.py val figures.png --each val/figures   # also one PNG a figure

Figures (each drawn only when its data is there; the others are skipped with a note):
  fig2-18  Ullner's time per ray against grid divisions n_s: the analytic model (seed 000
           L652 with L654's parameters) as a curve, the simulated points on the two-sheet scene
           (fig2-18.csv) and on the random squares (run folders), the seed's minimum 14.3 us
           at n_s = 11 (L654).
  fig2-21  intersections per ray against n_s: model (L614-L642) and simulated (fig2-18.csv).
  fig2-19  time per ray against n_s on the 83 cubes (run folders; the seed's values are lost,
           only the character survives, L662-L668).
  vax      the VAX-11/750 time per ray against the object count O: Gaudet's T_s + T_i O with
           T_i = 429 us, T_s = 710 us (seed 001 L317-L318, L326), the simulated runs, and the
           Fig 1-4 scene (O = 1093, about 238 h for 1,824,915 rays, L322-L326).
  fig6-10  Gaudet's ShellProcessor average processing and latency per ray for the binary,
           quad and oct trees (scenes 212, 412, 812; seed 001 L1025-L1030): thesis against
           simulated (rows P2a-P2c: processing as the value, latency in the note).
  fig6-11  Gaudet's ShellProcessor average latency per ray for breadth-first, depth-first and
           random broadcast order (scenes 404-420; seed 001 L1032-L1039): thesis against
           simulated (rows P4a, P4b: the per-scene latencies in their notes). The model does
           not reproduce this figure (P4 is open, docs/validation.md); the title says so.
  speedup  Gaudet's Figs 6-12..6-14: times faster than a VAX-11/750 against the number of
           PERTs, direct memory (dotted), non-adaptive (dashed) and adaptive (solid) broadcasting
           (gaudet-speedup.csv), with the thesis's two numbers: 20x for one PERT (L1141) and
           about 100x for eight (L1135, L1143). The thesis's graphs are lost (no values).
  summary  every row of the table: relative error against its tolerance.

Gaudet's values are taken, when `--keep` left them, from the run folders
(pert-SCENE-MODE-ORDER-nN/stats.json: gaudet.shell.processing_per_ray_s and
latency_per_ray_s), else from the rows `rtsim validate` writes (platform/validation/
gaudet_figures.cpp): P2a/P2b/P2c (binary 212, quad 412, oct 812) hold the processing per ray
as their value and "latency (emerges from the bus) X us per ray" in their note; P4a and P4b hold
"breadth a/b/c/d/e us, other f/g/h/i/j us" (scenes 404, 408, 412, 416, 420; other = depth-first
for P4a, random for P4b). Cells with no value are drawn from the thesis alone.
"""

import argparse
import glob
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

# ---- The seeds' numbers ----------------------------------------------------------------------

# Ullner 1983, Fig. 2-18 (seed 000 L652-L654): the model's parameters and its stated minimum.
ULLNER_T_I_US = 1.0 / 3.0  # L654 (and L588): one intersection every 1/3 us
ULLNER_T_D_US = 1.0        # L654: one microsecond to step to the next subvolume (assumed there)
ULLNER_T_L_US = 5.6        # L654 (L588): pipeline latency
ULLNER_D_R = 0.5           # L654: rays travel through about half of the modelling space
ULLNER_A_T = 2.0           # L654: surface area stretching through the space twice
ULLNER_N_P = 1000          # L654: a thousand polygons
ULLNER_MIN_NS = 11         # L654: "eleven subdivisions per axis"
ULLNER_MIN_US = 14.3       # L654: "14.3 microseconds per ray"
ULLNER_BRUTE_US = 1000.0 / 3.0  # L590: 1/3 ms per ray without subdivision

# Gaudet 1985, the VAX-11/750 baseline (seed 001 L310-L326).
VAX_T_I_US = 429.0           # L317: T_i, one ray/object intersection
VAX_T_S_US = 710.0           # L318: T_s, spawning (and shading) one ray
VAX_FIG14_OBJECTS = 1093     # L322: the Fig 1-4 scene's objects O
VAX_FIG14_RAYS = 1_824_915   # L324: its rays R_t
VAX_FIG14_HOURS = 238.0      # L326: "approximately 238 hours"

# Gaudet 1985, Fig 6-10 (seed 001 L1025-L1030): ShellProcessor, average times per ray (us).
GAUDET_FIG610 = {
    # tree: (scene, processing L1026, latency L1027, total L1028)
    "binary": (212, 467.8, 124.9, 592.7),
    "quad": (412, 523.9, 5.0, 528.9),
    "oct": (812, 690.5, 0.5, 691.0),
}

# Gaudet 1985, Fig 6-11 (seed 001 L1032-L1039): ShellProcessor, average latency per ray (us).
GAUDET_FIG611 = {
    # scene: (seed line, breadth-first, depth-first, random)
    404: (1033, 5.1, 11.4, 11.4),
    408: (1034, 4.7, 11.4, 11.3),
    412: (1035, 5.0, 12.0, 12.0),
    416: (1036, 5.1, 12.1, 11.9),
    420: (1037, 4.9, 11.9, 11.7),
}
GAUDET_ORDERS = ("breadth", "depth", "random")

FIGURES = ("fig2-18", "fig2-21", "fig2-19", "vax", "fig6-10", "fig6-11", "speedup",
           "summary")


def ullner_model_us(n_s, n_p=ULLNER_N_P, t_i=ULLNER_T_I_US, t_d=ULLNER_T_D_US, t_l=ULLNER_T_L_US,
                    d_r=ULLNER_D_R, a_t=ULLNER_A_T):
    """Time per ray (us), seed 000 L652:
    t_r = [(n_s - 1) d_r + 1] t_d + ((1 - 1/n_s) d_r n_s^-2 + [(n_s - 1) sqrt(a_t) + 1]^-2) n_p t_i
          + t_l"""
    steps = ((n_s - 1.0) * d_r + 1.0) * t_d
    tests = ((1.0 - 1.0 / n_s) * d_r / n_s**2 + ((n_s - 1.0) * math.sqrt(a_t) + 1.0) ** -2) * n_p
    return steps + tests * t_i + t_l


def ullner_model_intersections(n_s, n_p=ULLNER_N_P, d_r=ULLNER_D_R, a_t=ULLNER_A_T):
    """n_i of L652: the intersection term's count."""
    return ((1.0 - 1.0 / n_s) * d_r / n_s**2 + ((n_s - 1.0) * math.sqrt(a_t) + 1.0) ** -2) * n_p


# ---- Reading the validation folder -----------------------------------------------------------


class Validation:
    """What `rtsim validate --out DIR [--keep]` left in DIR."""

    def __init__(self, folder):
        if not os.path.isdir(folder):
            raise common.InputProblem(f"{folder}: not a folder (give the --out of rtsim validate)")
        self.folder = folder
        self.sensitivity = None  # scripts/gaudet_sensitivity.py --json, given by --sensitivity
        path = os.path.join(folder, "validation.json")
        self.rows = []
        if os.path.exists(path):
            data = common.read_json(path)
            self.rows = data.get("rows", []) if isinstance(data, dict) else []
        self.fig218 = self._read_csv(os.path.join(folder, "fig2-18.csv"))
        self.speedup = self._read_csv(os.path.join(folder, "gaudet-speedup.csv"))
        self.run_dirs = {}
        for d in sorted(glob.glob(os.path.join(folder, "runs-*", "*", "stats.json"))):
            self.run_dirs.setdefault(os.path.basename(os.path.dirname(d)), d)
        if (not self.rows and self.fig218 is None and self.speedup is None
                and not self.run_dirs):
            raise common.InputProblem(
                f"{folder}: no validation.json, fig2-18.csv, gaudet-speedup.csv or run folders")

    @staticmethod
    def _read_csv(path):
        if not os.path.exists(path):
            return None
        import pandas as pd

        try:
            return pd.read_csv(path)
        except Exception as e:
            raise common.InputProblem(f"{path}: not a CSV table: {e}")

    def row(self, rid):
        for r in self.rows:
            if r.get("id") == rid:
                return r
        return None

    def stats(self, key):
        p = self.run_dirs.get(key)
        return common.read_json(p) if p else None

    def sweep(self, prefix, path):
        """[(n_s, value)] from run folders PREFIX-nsNN, value at the dotted `path`."""
        out = []
        for key in self.run_dirs:
            m = re.fullmatch(re.escape(prefix) + r"-ns(\d+)", key)
            if not m:
                continue
            v = dig(self.stats(key), path)
            if common.finite(v):
                out.append((int(m.group(1)), float(v)))
        return sorted(out)


def dig(obj, path):
    for part in path.split("."):
        if not isinstance(obj, dict) or part not in obj:
            return None
        obj = obj[part]
    return obj


# ---- Gaudet's values ------------------------------------------------------------------------

_UNIT_TO_US = {"s": 1e6, "ms": 1e3, "us": 1.0, "µs": 1.0, "ns": 1e-3, "": 1.0}
GAUDET_FIG611_SCENES = (404, 408, 412, 416, 420)  # the order of P4's note (L1033-L1037)
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def row_value_us(row):
    v = row.get("simulated_value")
    if not common.finite(v):
        return None
    unit = (row.get("unit") or "").strip()
    return float(v) * _UNIT_TO_US.get(unit, 1.0)


def _rows_with_prefix(rows, prefix):
    return [r for r in rows if re.fullmatch(re.escape(prefix) + r"[a-z]?", str(r.get("id", "")))]


def _run_us(val, key, path):
    v = dig(val.stats(key), path)
    return float(v) * 1e6 if common.finite(v) else None


def gaudet_fig610(val):
    """{tree: {"processing": us, "latency": us}} simulated, for the trees of Fig 6-10: from the
    run folders pert-SCENE-adaptive-breadth-n1 if kept, else from rows P2a-P2c (the scene
    number in the title picks the tree; processing is the value, latency is in the note)."""
    out = {}
    rows = _rows_with_prefix(val.rows, "P2")
    for tree, (scene, *_) in GAUDET_FIG610.items():
        cell = {}
        key = f"pert-{scene}-adaptive-breadth-n1"
        for q in ("processing", "latency"):
            v = _run_us(val, key, f"gaudet.shell.{q}_per_ray_s")
            if v is not None:
                cell[q] = v
        row = next((r for r in rows if f"({scene})" in str(r.get("title", ""))), None)
        if row is not None:
            if "processing" not in cell and row_value_us(row) is not None:
                cell["processing"] = row_value_us(row)
            m = re.search(rf"latency[^0-9]*?({_NUMBER}) us per ray", str(row.get("note", "")))
            if "latency" not in cell and m:
                cell["latency"] = float(m.group(1))
        if cell:
            out[tree] = cell
    return out


def _note_series(row, word):
    """The five numbers after `word` in a P4 note ("breadth 4.1/6.5/13.7/16.5/18.7 us")."""
    m = re.search(rf"{word} ({_NUMBER}(?:/{_NUMBER})*) us", str(row.get("note", "")))
    if not m:
        return None
    values = [float(x) for x in m.group(1).split("/")]
    return values if len(values) == len(GAUDET_FIG611_SCENES) else None


def gaudet_fig611(val):
    """{(scene, order): us} simulated ShellProcessor latency per ray for Fig 6-11: from the run
    folders pert-SCENE-adaptive-ORDER-n1 if kept, else from the notes of P4a (breadth, and
    depth-first as "other") and P4b (random as "other")."""
    out = {}
    for scene in GAUDET_FIG611_SCENES:
        for order in GAUDET_ORDERS:
            v = _run_us(val, f"pert-{scene}-adaptive-{order}-n1", "gaudet.shell.latency_per_ray_s")
            if v is not None:
                out[(scene, order)] = v
    for rid, order in (("P4a", "depth"), ("P4b", "random")):
        row = val.row(rid)
        if row is None:
            continue
        for word, o in (("breadth", "breadth"), ("other", order)):
            values = _note_series(row, word)
            if values:
                for scene, v in zip(GAUDET_FIG611_SCENES, values):
                    out.setdefault((scene, o), v)
    return out


def gaudet_order_verdict(val):
    """What the validation said of Fig 6-11: "not reproduced (P4a, P4b fail)", "reproduced
    (P4a, P4b pass)", or None without P4 rows."""
    rows = [r for r in (val.row("P4a"), val.row("P4b")) if r is not None]
    if not rows:
        return None
    ids = ", ".join(r["id"] for r in rows)
    if all(r.get("pass") for r in rows):
        return f"reproduced ({ids} pass)"
    failing = ", ".join(r["id"] for r in rows if not r.get("pass"))
    return f"NOT reproduced ({failing} fail{'s' if ',' not in failing else ''})"


def gaudet_speedup(val):
    """{scene: {mode: (pert counts, times faster than the VAX-11/750)}} from gaudet-speedup.csv
    (columns scene, mode, pert_count, frame_s, vax_frame_s, speedup_over_vax)."""
    df = val.speedup
    if df is None:
        return {}
    need = {"scene", "mode", "pert_count", "speedup_over_vax"}
    if not need <= set(df.columns):
        raise common.InputProblem(f"{val.folder}/gaudet-speedup.csv: expected the columns "
                                  f"{', '.join(sorted(need))}; got {', '.join(df.columns)}")
    out = {}
    for (scene, mode), g in df.groupby(["scene", "mode"], sort=False):
        g = g.sort_values("pert_count")
        out.setdefault(str(scene), {})[str(mode)] = (g["pert_count"].to_numpy(float),
                                                     g["speedup_over_vax"].to_numpy(float))
    return out


# ---- The figures -----------------------------------------------------------------------------


def series_fig218(val):
    """{"model": (n, us), "simulated": ..., "model_measured_d_r": ..., "random": ...}."""
    import numpy as np

    n = np.linspace(1.0, 30.0, 291)
    out = {"model": (n, np.array([ullner_model_us(x) for x in n]))}
    if val.fig218 is not None and "simulated_t_r_us" in val.fig218:
        df = val.fig218.sort_values("n_s")
        out["simulated"] = (df["n_s"].to_numpy(float), df["simulated_t_r_us"].to_numpy(float))
        if "model_t_r_measured_d_r_us" in df:
            out["model_measured_d_r"] = (df["n_s"].to_numpy(float),
                                         df["model_t_r_measured_d_r_us"].to_numpy(float))
    random = val.sweep("peripheral-grid-random", "peripheral.time_per_ray_s")
    if random:
        out["random"] = (np.array([p[0] for p in random], float),
                         np.array([p[1] * 1e6 for p in random]))
    return out


def draw_fig218(ax, val):
    s = series_fig218(val)
    ax.plot(*s["model"], "k-", label="model, L652 with L654's parameters")
    if "model_measured_d_r" in s:
        ax.plot(*s["model_measured_d_r"], "k:", label="model with the measured d_r")
    if "simulated" in s:
        ax.plot(*s["simulated"], "o-", color="tab:blue", ms=4,
                label="simulated: two sheets (ullner-sheets-1000)")
    if "random" in s:
        ax.plot(*s["random"], "s--", color="tab:orange", ms=4,
                label="simulated: random squares (ullner-random-1000)")
    ax.plot([ULLNER_MIN_NS], [ULLNER_MIN_US], "r*", ms=13, label="seed: 14.3 µs at n_s = 11 (L654)")
    ax.set_yscale("log")
    common.log_axis(ax.yaxis)
    common.integer_axis(ax.xaxis)
    ax.set_xlabel("subdivisions per axis n_s")
    ax.set_ylabel("time per ray (µs)")
    ax.set_title("Fig. 2-18: time per ray against grid divisions")
    return {"fontsize": "x-small"}


def draw_fig221(ax, val):
    import numpy as np

    if val.fig218 is None or "simulated_tests_per_ray" not in val.fig218:
        return None
    df = val.fig218.sort_values("n_s")
    n = np.linspace(1.0, 30.0, 291)
    ax.plot(n, [ullner_model_intersections(x) for x in n], "k-", label="model n_i (L652)")
    ax.plot(df["n_s"], df["simulated_tests_per_ray"], "o-", ms=4, label="simulated: two sheets")
    ax.set_yscale("log")
    common.log_axis(ax.yaxis)
    common.integer_axis(ax.xaxis)
    ax.set_xlabel("subdivisions per axis n_s")
    ax.set_ylabel("intersections per ray")
    ax.set_title("Fig. 2-21: intersections per ray")
    return {"fontsize": "x-small"}


def draw_fig219(ax, val):
    cubes = val.sweep("peripheral-cubes", "peripheral.time_per_ray_s")
    if not cubes:
        return None
    ax.plot([p[0] for p in cubes], [p[1] * 1e6 for p in cubes], "o-", ms=4,
            label="simulated: 83 cubes (ullner-cubes)")
    best = min(cubes, key=lambda p: p[1])
    ax.plot([best[0]], [best[1] * 1e6], "r*", ms=12, label=f"minimum at n_s = {best[0]}")
    common.integer_axis(ax.xaxis)
    ax.set_xlabel("subdivisions per axis n_s")
    ax.set_ylabel("time per ray (µs)")
    ax.set_title("Fig. 2-19: 83 cubes (seed values lost: shape only)")
    return {"fontsize": "x-small"}


def series_vax(val):
    """Simulated (O, ms per ray) points from the VAX runs, and the recovered T_i, T_s (us)."""
    points = []
    for key in ("vax-default", "vax-cubes"):
        st = val.stats(key)
        if not st:
            continue
        rays, objects, t = (dig(st, "rays.total"), dig(st, "scene_stats.primitives"),
                            dig(st, "simulated_time_s"))
        if common.finite(rays) and rays > 0 and common.finite(objects) and common.finite(t):
            points.append((float(objects), float(t) / float(rays) * 1e3))
    recovered = {}
    for rid, name in (("VAX3", "t_i_us"), ("VAX4", "t_s_us")):
        r = val.row(rid)
        if r and common.finite(r.get("simulated_value")):
            recovered[name] = row_value_us(r)
    return sorted(points), recovered


def draw_vax(ax, val):
    import numpy as np

    points, rec = series_vax(val)
    if not points and len(rec) < 2:
        return None
    o = np.linspace(0, VAX_FIG14_OBJECTS * 1.05, 50)
    ax.plot(o, (VAX_T_S_US + VAX_T_I_US * o) / 1e3, "k-",
            label="seed: T_s + T_i O, 710 + 429 O µs (L317-L318)")
    if len(rec) == 2:
        ax.plot(o, (rec["t_s_us"] + rec["t_i_us"] * o) / 1e3, "--", color="tab:orange",
                label=f"recovered: {rec['t_s_us']:.4g} + {rec['t_i_us']:.4g} O µs (VAX3, VAX4)")
    if points:
        ax.plot([p[0] for p in points], [p[1] for p in points], "o", color="tab:blue", ms=6,
                label="simulated runs (vax-750)")
    per_ray_ms = VAX_FIG14_HOURS * 3600.0 / VAX_FIG14_RAYS * 1e3
    ax.plot([VAX_FIG14_OBJECTS], [per_ray_ms], "r*", ms=12,
            label="seed: Fig 1-4 scene, 238 h / 1,824,915 rays (L322-L326)")
    common.integer_axis(ax.xaxis)
    ax.set_xlabel("objects O")
    ax.set_ylabel("time per ray (ms)")
    ax.set_title("VAX-11/750: time per ray, T_t = R_t (T_s + T_i O)")
    return {"fontsize": "x-small"}


def draw_fig610(ax, val):
    import numpy as np

    sim = gaudet_fig610(val)
    trees = list(GAUDET_FIG610)
    x = np.arange(len(trees))
    w = 0.38
    proc = [GAUDET_FIG610[t][1] for t in trees]
    lat = [GAUDET_FIG610[t][2] for t in trees]
    ax.bar(x - w / 2, proc, w, color="tab:blue", alpha=0.4, label="thesis: processing (L1026)")
    ax.bar(x - w / 2, lat, w, bottom=proc, color="tab:red", alpha=0.4,
           label="thesis: latency (L1027)")
    labelled = False
    for i, t in enumerate(trees):
        ax.annotate(f"lat {lat[i]:g}", (x[i] - w / 2, proc[i] + lat[i]), ha="center",
                    va="bottom", fontsize="x-small")
        cell = sim.get(t, {})
        p, latency = cell.get("processing"), cell.get("latency")
        if p is not None:
            ax.bar(x[i] + w / 2, p, w, color="tab:blue",
                   label=None if labelled else "simulated: processing")
        if latency is not None:
            ax.bar(x[i] + w / 2, latency, w, bottom=p or 0.0, color="tab:red",
                   label=None if labelled else "simulated: latency")
            ax.annotate(f"lat {latency:.3g}", (x[i] + w / 2, (p or 0.0) + latency),
                        ha="center", va="bottom", fontsize="x-small")
        labelled |= p is not None or latency is not None
    # The sensitivity of the simulated bars to the open assumptions (docs/validation.md): each
    # setting's processing + latency, as a marker beside the simulated bar.
    rows = (val.sensitivity or {}).get("settings", [])
    markers = "ov^sD"
    for k, row in enumerate(rows):
        ys = []
        for t in trees:
            cell = row.get("trees", {}).get(str(GAUDET_FIG610[t][0]), {})
            ys.append(cell.get("processing_us", float("nan")) + cell.get("latency_us", float("nan")))
        offset = w / 2 + w * (k + 1) / (len(rows) + 1) - w / 2
        ax.plot(x + offset, ys, linestyle="none", marker=markers[k % len(markers)], markersize=4,
                color="black", alpha=0.7, label=row.get("setting", f"setting {k + 1}"))
    ax.set_xticks(x)
    ax.set_xticklabels([f"{t} ({GAUDET_FIG610[t][0]})" for t in trees])
    ax.set_ylabel("ShellProcessor time per ray (µs)")
    ax.set_ylim(0, max(a + b for a, b in zip(proc, lat)) * (1.6 if rows else 1.25))
    note = "" if sim else " — no simulated values"
    ax.set_title(f"Fig 6-10: processing + latency per ray, left thesis, right simulated{note}",
                 fontsize="small")
    return {"fontsize": "x-small", "ncol": 2}


def draw_fig611(ax, val):
    sim = gaudet_fig611(val)
    scenes = list(GAUDET_FIG611_SCENES)
    colors = {"breadth": "tab:blue", "depth": "tab:red", "random": "tab:green"}
    for k, order in enumerate(GAUDET_ORDERS):
        name = "random" if order == "random" else f"{order}-first"
        ax.plot(scenes, [GAUDET_FIG611[s][1 + k] for s in scenes], "--", color=colors[order],
                alpha=0.6, marker="x", label=f"thesis: {name}")
        pts = [(s, sim[(s, order)]) for s in scenes if (s, order) in sim]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=colors[order],
                    label=f"simulated: {name}")
    ax.set_xticks(scenes)
    ax.set_xlabel("scene (4-ary tree, 4..20 spheres per cluster)")
    ax.set_ylabel("ShellProcessor latency per ray (µs)")
    verdict = gaudet_order_verdict(val)
    if not sim:
        note = " — no simulated values"
    elif verdict:
        note = f" — {verdict}"
    else:
        note = ""
    ax.set_title(f"Fig 6-11: broadcast order (L1032-L1039){note}", fontsize="small",
                 color="tab:red" if verdict and verdict.startswith("NOT") else "black")
    return {"fontsize": "x-small", "ncol": 2}


def draw_speedup(ax, val):
    curves = gaudet_speedup(val)
    if not curves:
        return None
    styles = {"direct": ":", "non-adaptive": "--", "adaptive": "-"}
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown"]
    for k, (scene, modes) in enumerate(curves.items()):
        for mode, (ns, ys) in modes.items():
            ax.plot(ns, ys, styles.get(mode, "-."), marker="o", ms=3,
                    color=colors[k % len(colors)], label=f"{scene} {mode}")
    ax.plot([1], [20], "r*", ms=13, label="thesis: 1 PERT 20x (L1141)")
    ax.plot([8], [100], "rP", ms=11, label="thesis: 8 PERTs ~100x (L1135, L1143)")
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    ax.set_xscale("log", base=2)
    counts = sorted({int(n) for modes in curves.values() for ns, _ in modes.values() for n in ns})
    ax.xaxis.set_major_locator(FixedLocator(counts))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: common.plain_number(v)))
    ax.set_yscale("log")
    common.log_axis(ax.yaxis)
    ax.set_xlabel("PERTs n")
    ax.set_ylabel("times faster than the VAX-11/750")
    ax.set_title("Figs 6-12..6-14: speed-up over the VAX (thesis graphs lost; dotted direct, "
                 "dashed non-adaptive, solid adaptive)", fontsize="small")
    return {"fontsize": "xx-small", "ncol": 2}


def draw_summary(ax, val):
    every = [r for r in val.rows if r.get("id")]
    if not every:
        return None
    # Only the figures with a relative error have a bar: the others (exact counts, orders,
    # ranges) would be empty ticks crowding the labels.
    rows = [r for r in every if common.finite(r.get("relative_error"))]
    ids = [r["id"] for r in rows]
    errs = [100.0 * float(r["relative_error"]) for r in rows]
    colors = ["tab:green" if r.get("pass") else "tab:red" for r in rows]
    ax.bar(range(len(ids)), errs, color=colors)
    for i, r in enumerate(rows):
        tol = r.get("tolerance") or {}
        if tol.get("kind") == "relative" and common.finite(tol.get("value")):
            t = 100.0 * float(tol["value"])
            ax.plot([i - 0.4, i + 0.4], [t, t], "k-", lw=0.8)
            ax.plot([i - 0.4, i + 0.4], [-t, -t], "k-", lw=0.8)
    ax.set_xticks(range(len(ids)))
    ax.set_xticklabels(ids, rotation=90, fontsize=7 if len(ids) <= 60 else 5)
    ax.set_xlim(-0.6, len(ids) - 0.4)
    ax.grid(False, axis="x")
    ax.set_ylabel("relative error (%)")
    ax.axhline(0, color="k", lw=0.5)
    passed = sum(1 for r in every if r.get("pass"))
    ax.set_title(f"All figures: {passed} of {len(every)} pass; the {len(rows)} with a relative "
                 "error (bars: error; lines: tolerance)", fontsize="small")
    return {}


# Each draws its figure on an axes and returns its legend's options (a dict), or None when the
# folder has no data for it.
DRAW = {"fig2-18": draw_fig218, "fig2-21": draw_fig221, "fig2-19": draw_fig219, "vax": draw_vax,
        "fig6-10": draw_fig610, "fig6-11": draw_fig611, "speedup": draw_speedup,
        "summary": draw_summary}


def render(val, names, out_path):
    """Draw `names` into one PNG (a grid of panels); returns the names drawn."""
    plt = common.pyplot()
    # Draw each on a scratch figure first to know which have data.
    drawable = []
    for name in names:
        fig, ax = plt.subplots()
        if DRAW[name](ax, val) is not None:
            drawable.append(name)
        else:
            print(f"figures.py: {name}: no data in {val.folder}; skipped", file=sys.stderr)
        plt.close(fig)
    if not drawable:
        raise common.InputProblem(f"{val.folder}: none of {', '.join(names)} has data")
    cols = 1 if len(drawable) == 1 else 2
    nrows = (len(drawable) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(7.5 * cols, 4.8 * nrows), squeeze=False)
    legends = []
    for k, name in enumerate(drawable):
        ax = axes[k // cols][k % cols]
        legends.append((ax, DRAW[name](ax, val)))
        ax.grid(True, which="both", alpha=0.3)
    for k in range(len(drawable), nrows * cols):
        axes[k // cols][k % cols].set_axis_off()
    fig.tight_layout()
    for ax, options in legends:
        if ax.get_legend_handles_labels()[0]:
            common.place_legend(ax, **options)
    fig.tight_layout()  # room for legends that went beside their panel
    common.save(fig, out_path)
    plt.close(fig)
    return drawable


def main(argv):
    ap = argparse.ArgumentParser(
        prog="figures.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="the --out folder of `rtsim validate` (use --keep for curves)")
    ap.add_argument("out", help="PNG to write (all the figures drawn, as panels)")
    ap.add_argument("--figure", default="all", help=f"all, or one or more of {', '.join(FIGURES)} "
                    "(comma-separated)")
    ap.add_argument("--each", default=None, metavar="DIR",
                    help="also write each figure drawn as DIR/NAME.png")
    ap.add_argument("--sensitivity", default=None, metavar="JSON",
                    help="fig6-10 also marks processing + latency at each setting of "
                    "`scripts/gaudet_sensitivity.py --json JSON` (the open assumptions)")
    args = ap.parse_args(argv)
    names = list(FIGURES) if args.figure == "all" else [s.strip() for s in args.figure.split(",")]
    for n in names:
        if n not in DRAW:
            raise common.InputProblem(f"--figure: no figure '{n}' (known: {', '.join(FIGURES)})")
    val = Validation(args.input)
    if args.sensitivity:
        data = common.read_json(args.sensitivity)
        if not isinstance(data, dict) or not isinstance(data.get("settings"), list):
            raise common.InputProblem(f"{args.sensitivity}: expected the --json output of "
                                      "scripts/gaudet_sensitivity.py (a 'settings' list)")
        val.sensitivity = data
    drawn = render(val, names, args.out)
    if args.each:
        for name in drawn:
            render(val, [name], os.path.join(args.each, f"{name}.png"))
    print(f"figures.py: drew {', '.join(drawn)} into {args.out}")
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
