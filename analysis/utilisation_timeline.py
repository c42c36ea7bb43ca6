#!/usr/bin/python3
"""Bus and module utilisation over simulated time: the busy fraction of each module in each
time window, and the mean depth of each queue.

    /usr/bin/python3 analysis/utilisation_timeline.py out/run/trace.json util.png --windows 200
    /usr/bin/python3 analysis/utilisation_timeline.py out/run/stats.json util.png
    /usr/bin/python3 analysis/utilisation_timeline.py out/run util.png     # trace.json if there, else stats.json

From a Perfetto/Chrome JSON trace (`rtsim run --trace perfetto`): each module's busy counter
("C" events NAME.busy: the level of the very busy intervals stats.json's busy_s is summed from)
gives its busy fraction per window, as its time-weighted mean; each queue's depth counter
(NAME.depth) its time-weighted mean depth. A track with slices ("X" events) but no busy counter
(a trace from elsewhere) gives the fraction of each window covered by the union of its slices.
The time range is the frame (otherData rtsim_stats_interval_s, written by rtsim) for a trace of
the whole run, the trace's window (rtsim_window_s) for one narrowed by --trace-window, else from
the first to the last event.

From stats.json: `modules.NAME.utilization_windows` {begin_s, window_s, values}, which
`rtsim run` records for every timed module in 100 windows of the frame (docs/stats.md). No
queue depths there.
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

US = 1e-6  # the trace format's time unit is the microsecond


def load(path, source="auto"):
    """("trace" | "stats", parsed JSON) for a trace, a stats.json or a run folder."""
    if os.path.isdir(path):
        candidates = {"trace": "trace.json", "stats": "stats.json"}
        order = ["trace", "stats"] if source == "auto" else [source]
        for kind in order:
            p = os.path.join(path, candidates[kind])
            if os.path.exists(p):
                return kind, common.read_json(p)
        raise common.InputProblem(f"{path}: no {' or '.join(candidates[k] for k in order)} here")
    data = common.read_json(path)
    if isinstance(data, dict) and "traceEvents" in data:
        kind = "trace"
    elif isinstance(data, list):
        kind, data = "trace", {"traceEvents": data}  # the JSON array form of the format
    elif isinstance(data, dict) and "modules" in data:
        kind = "stats"
    else:
        raise common.InputProblem(f"{path}: neither a Perfetto/Chrome trace (traceEvents) nor "
                                  "an rtsim stats.json (modules)")
    if source != "auto" and source != kind:
        raise common.InputProblem(f"{path}: is a {kind} file, not a {source} file")
    return kind, data


def _edges(begin, end, windows, window_s):
    import numpy as np

    if end <= begin:
        raise common.InputProblem("the trace spans no time (no events, or all at one instant)")
    if window_s:
        n = max(1, int(np.ceil((end - begin) / window_s - 1e-9)))
        return begin + window_s * np.arange(n + 1)
    return np.linspace(begin, end, int(windows) + 1)


def _busy_in_windows(starts, ends, edges):
    """Busy time of the union of [starts, ends) in each window of `edges` (all in seconds)."""
    import numpy as np

    order = np.argsort(starts, kind="stable")
    s, e = starts[order], ends[order]
    # Union of intervals: merge each one that starts before the running end.
    run_end = np.maximum.accumulate(e)
    new = np.ones(len(s), dtype=bool)
    new[1:] = s[1:] > run_end[:-1]
    idx = np.flatnonzero(new)
    ms = s[idx]
    me = np.maximum.reduceat(e, idx) if len(idx) else e[:0]
    # Cumulative busy time B(t) at the window edges.
    lengths = me - ms
    before = np.concatenate(([0.0], np.cumsum(lengths)))[:-1]
    j = np.searchsorted(ms, edges, side="right") - 1
    jj = np.clip(j, 0, max(len(ms) - 1, 0))
    b = np.where(j < 0, 0.0, before[jj] + np.clip(edges - ms[jj], 0.0, lengths[jj]))
    return np.diff(b)


def _mean_level_in_windows(times, values, edges):
    """Time-weighted mean of a step function (value holds from its time to the next)."""
    import numpy as np

    order = np.argsort(times, kind="stable")
    t, v = times[order], values[order]
    # Integral I(t) up to each event time: the level before the first event is 0.
    seg = np.diff(t) * v[:-1]
    at = np.concatenate(([0.0], np.cumsum(seg)))
    j = np.searchsorted(t, edges, side="right") - 1
    jj = np.clip(j, 0, len(t) - 1)
    integral = np.where(j < 0, 0.0, at[jj] + (edges - t[jj]) * v[jj])
    return np.diff(integral) / np.diff(edges)


def busy_from_trace(trace, windows=100, window_s=None, modules=None):
    """(edges_s, {track: busy fraction per window}, {counter: mean value per window}).

    Times are absolute simulated seconds. `modules` is an optional regular expression on the
    track names."""
    import numpy as np

    events = trace.get("traceEvents", [])
    names = {}
    slices = {}
    counters = {}
    lo, hi = np.inf, -np.inf
    for ev in events:
        ph = ev.get("ph")
        if ph == "M" and ev.get("name") == "thread_name":
            names[(ev.get("pid"), ev.get("tid"))] = ev.get("args", {}).get("name")
        elif ph == "X":
            ts = float(ev["ts"]) * US
            dur = float(ev.get("dur", 0.0)) * US
            slices.setdefault((ev.get("pid"), ev.get("tid")), []).append((ts, ts + dur))
            lo, hi = min(lo, ts), max(hi, ts + dur)
        elif ph == "C":
            ts = float(ev["ts"]) * US
            for key, value in ev.get("args", {}).items():
                name = ev.get("name", "counter") + ("" if key == "value" else "." + key)
                counters.setdefault(name, []).append((ts, float(value)))
            lo, hi = min(lo, ts), max(hi, ts)
    if not slices and not counters:
        raise common.InputProblem("the trace has no slices or counters")
    other = trace.get("otherData", {})
    window = other.get("rtsim_window_s")
    frame = other.get("rtsim_stats_interval_s")
    if window and float(window[1]) > float(window[0]):
        lo, hi = float(window[0]), float(window[1])
        # A trace of the whole run is drawn over the frame, as stats.json's windows are (the
        # scene load before it would only dilute the first window).
        if frame and lo == 0.0 and hi >= float(frame[1]) and float(frame[1]) > float(frame[0]):
            lo, hi = float(frame[0]), float(frame[1])
    edges = _edges(lo, hi, windows, window_s)
    pattern = re.compile(modules) if modules else None
    busy = {}
    depth = {}
    for name, pts in sorted(counters.items()):
        a = np.array(pts, dtype=float)
        if name.endswith(".busy"):
            module = name[:-len(".busy")]
            if not (pattern and not pattern.search(module)):
                busy[module] = _mean_level_in_windows(a[:, 0], a[:, 1], edges)
            continue
        if pattern and not pattern.search(name):
            continue
        depth[name] = _mean_level_in_windows(a[:, 0], a[:, 1], edges)
    for key, iv in sorted(slices.items(), key=lambda kv: str(names.get(kv[0], kv[0]))):
        name = names.get(key) or f"pid {key[0]} tid {key[1]}"
        if name in busy or (name + ".busy") in counters:
            continue  # the busy counter is the module's busy time; slices are its transactions
        if pattern and not pattern.search(name):
            continue
        a = np.array(iv, dtype=float)
        busy[name] = _busy_in_windows(a[:, 0], a[:, 1], edges) / np.diff(edges)
    busy = dict(sorted(busy.items()))
    return edges, busy, depth


def busy_from_stats(stats, modules=None):
    """(edges_s, {module: busy fraction per window}) from utilization_windows in stats.json."""
    import numpy as np

    pattern = re.compile(modules) if modules else None
    out = {}
    edges = None
    for name, m in sorted(stats.get("modules", {}).items()):
        w = m.get("utilization_windows") or m.get("utilisation_windows")
        if not w or not w.get("values"):
            continue
        if pattern and not pattern.search(name):
            continue
        values = np.array(w["values"], dtype=float)
        e = float(w["begin_s"]) + float(w["window_s"]) * np.arange(len(values) + 1)
        if edges is None:
            edges = e
        elif len(e) != len(edges) or not np.allclose(e, edges, rtol=1e-9, atol=0.0):
            print(f"utilisation_timeline: {name} has other windows; drawn on its own",
                  file=sys.stderr)
        out[name] = (e, values)
    if not out:
        raise common.InputProblem("stats.json has no modules.NAME.utilization_windows (written "
                                  "by `rtsim run` of a timed machine)")
    return edges, out


# More series than this in one panel are drawn by class (module_groups).
MOST_SERIES = 12


def module_groups(series, most=MOST_SERIES):
    """{label: (edges, mean, low, high)}: the series as they are when there are at most `most`;
    else the instances of a class (names equal but for their numbers: pert0.shell ...
    pert63.shell) with the same windows as one group, its mean and its min-max band (low and
    high None for a single series)."""
    import numpy as np

    if len(series) <= most:
        return {name: (e, np.asarray(v, float), None, None) for name, (e, v) in series.items()}
    classes = {}
    for name, (e, v) in series.items():
        classes.setdefault(common.instance_pattern(name), []).append((name, e, v))
    out = {}
    for pattern, members in classes.items():
        edges = np.asarray(members[0][1], float)
        same = all(np.array_equal(np.asarray(e, float), edges) for _, e, _ in members)
        if len(members) == 1 or not same:
            for name, e, v in members:
                out[name] = (e, np.asarray(v, float), None, None)
            continue
        values = np.array([np.asarray(v, float) for _, _, v in members])
        out[f"{pattern} ({len(members)}: mean, min-max)"] = (
            edges, values.mean(axis=0), values.min(axis=0), values.max(axis=0))
    return out


def draw(busy_series, depth_series, title):
    """(fig, axes): busy_series and depth_series are {name: (edges, values)}; time from the
    first edge, in one unit (ns, µs, ms, s or h) chosen from the range drawn."""
    import numpy as np

    plt = common.pyplot()
    start = min(e[0] for e, _ in busy_series.values()) if busy_series else min(
        e[0] for e, _ in depth_series.values())
    end = max(e[-1] for e, _ in list(busy_series.values()) + list(depth_series.values()))
    scale, unit = common.time_unit(end - start)
    rows = 2 if depth_series else 1
    fig, axes = plt.subplots(rows, 1, figsize=(8, 3.2 * rows + 0.6), sharex=True, squeeze=False)
    ax = axes[0][0]
    for name, (e, v, low, high) in module_groups(busy_series).items():
        x = (np.asarray(e) - start) * scale
        line = ax.stairs(100.0 * v, x, label=name, linewidth=1.4)
        if low is not None:
            ax.stairs(100.0 * high, x, baseline=100.0 * low, fill=True, alpha=0.2,
                      color=line.get_edgecolor(), zorder=0.5)
    ax.set_ylabel("busy (%)")
    ax.set_ylim(-2, 102)
    ax.grid(True, alpha=0.3)
    ax.set_title(title)
    if depth_series:
        ax2 = axes[1][0]
        for name, (e, v, low, high) in module_groups(depth_series).items():
            x = (np.asarray(e) - start) * scale
            line = ax2.stairs(v, x, label=name, linewidth=1.4)
            if low is not None:
                ax2.stairs(high, x, baseline=low, fill=True, alpha=0.2,
                           color=line.get_edgecolor(), zorder=0.5)
        ax2.set_ylabel("mean queue depth")
        ax2.grid(True, alpha=0.3)
    axes[-1][0].set_xlabel(f"simulated time ({unit}) after t = {common.seconds_text(start)}")
    for a in axes[:, 0]:
        if a.get_legend_handles_labels()[0]:
            common.place_legend(a, fontsize="small")
    return fig, axes[:, 0]


def main(argv):
    ap = argparse.ArgumentParser(
        prog="utilisation_timeline.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="trace.json, stats.json, or a run folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--source", choices=("auto", "trace", "stats"), default="auto",
                    help="which input to read in a folder (auto: the trace if there is one)")
    ap.add_argument("--windows", type=int, default=100,
                    help="trace: number of equal windows over the trace (default 100)")
    ap.add_argument("--window", type=float, default=None, metavar="SECONDS",
                    help="trace: window width in simulated seconds (instead of --windows)")
    ap.add_argument("--modules", default=None, metavar="REGEX",
                    help="only tracks/modules whose name matches")
    ap.add_argument("--title", default=None)
    args = ap.parse_args(argv)
    if args.windows < 1:
        raise common.InputProblem("--windows must be at least 1")
    if args.window is not None and not args.window > 0:
        raise common.InputProblem("--window must be > 0")
    kind, data = load(args.input, args.source)
    if kind == "trace":
        edges, busy, depth = busy_from_trace(data, args.windows, args.window, args.modules)
        busy_series = {k: (edges, v) for k, v in busy.items()}
        depth_series = {k: (edges, v) for k, v in depth.items()}
        title = args.title or "Utilisation over time (Perfetto trace)"
    else:
        _, series = busy_from_stats(data, args.modules)
        busy_series, depth_series = series, {}
        title = args.title or (f"Utilisation over time: {data.get('machine', '?')} on "
                               f"{data.get('scene', '?')}")
    if not busy_series and not depth_series:
        raise common.InputProblem("nothing to draw (no track matches)")
    fig, _ = draw(busy_series, depth_series, title)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
