#!/usr/bin/python3
"""Plot any column of a sweep's results table against any other, one line per scene or
machine (or any grouping column).

    /usr/bin/python3 analysis/sweep_plot.py results.csv out.png --x peripheral.grid.divisions \\
        --y peripheral.time_per_ray_s --logy
    /usr/bin/python3 analysis/sweep_plot.py results.jsonl speedup.png --x pert_count \\
        --y simulated_time_s --ratio-to pert_count=1     # speed-up over the 1-PERT point

INPUT is results.csv or results.jsonl from `rtsim sweep` (one row per point: the swept
parameters, machine, scene, headline stats such as simulated_time_s, wall_time_s, rays.total,
modules.NAME.utilization), or a folder holding one of them. Nested JSON objects become dotted
column names; extra columns are ignored. Rows whose exit status or status says the point
failed are left out. Values written with units ("400 ns", "5 MHz") are read in the SI base
unit. `utilisation` and `utilization` name the same column.

Times (columns named *_s, such as simulated_time_s and ray_latency_s.mean, and values written
in seconds, such as "250 ns") are drawn in one unit per axis, ns, µs, ms, s or h, chosen from
their range and named in the axis label ("(s)" in --xlabel or --ylabel becomes that unit).
Lines are listed in the order of their values ("250 ns" before "1000 ns").

--ratio-to draws y as a ratio to a baseline: COL=VALUE takes, in each group, the row where COL
equals VALUE (e.g. the 1-PERT run); a bare column name divides by that column row by row.
--ratio-mode speedup (default) plots baseline / y, fraction plots y / baseline.

--y may be given several times (e.g. each module's utilisation): one line per column (and per
group), labelled by what differs between the column names.

--band Y=LOW,HIGH shades, around the line of the --y column Y, the range from column LOW to
column HIGH (a class of module instances: its mean drawn, from its least to its busiest
instance shaded, module_classes.node*.utilization.mean=...min,...max).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def read_results(path):
    """The results table as a pandas DataFrame (CSV or JSON lines, or a folder with one)."""
    import pandas as pd

    if os.path.isdir(path):
        for name in ("results.jsonl", "results.csv"):
            if os.path.exists(os.path.join(path, name)):
                path = os.path.join(path, name)
                break
        else:
            raise common.InputProblem(f"{path}: no results.jsonl or results.csv in this folder")
    if not os.path.exists(path):
        raise common.InputProblem(f"{path}: no such file")
    if path.endswith(".jsonl") or path.endswith(".json"):
        import json

        rows = []
        with open(path, encoding="utf-8") as f:
            for lineno, line in enumerate(f, 1):
                if not line.strip():
                    continue
                try:
                    obj = json.loads(line)
                except json.JSONDecodeError as e:
                    raise common.InputProblem(f"{path}:{lineno}: not JSON: {e.msg}")
                if not isinstance(obj, dict):
                    raise common.InputProblem(f"{path}:{lineno}: expected a JSON object")
                rows.append(common.flatten(obj))
        return pd.DataFrame(rows)
    try:
        return pd.read_csv(path)
    except Exception as e:  # pandas raises several parser errors
        raise common.InputProblem(f"{path}: not a CSV table: {e}")


def ok_rows(df):
    """Leave out the points that failed (exit status not 0, status not ok, an error text)."""
    import pandas as pd

    keep = pd.Series(True, index=df.index)
    for col in ("exit_status", "exit_code"):
        if col in df.columns:
            codes = df[col].map(common.to_number)
            keep &= codes.isna() | (codes == 0)
    if "status" in df.columns:
        st = df["status"].fillna("").astype(str).str.lower()
        keep &= st.isin(["", "ok", "done", "success", "succeeded", "passed", "pass", "0"])
    if "error" in df.columns:
        keep &= df["error"].fillna("").astype(str).str.strip() == ""
    return df[keep]


def default_group(df):
    for col in ("scene", "machine"):
        if col in df.columns and df[col].nunique(dropna=True) > 1:
            return col
    return None


def _numeric(series):
    nums = series.map(common.to_number)
    return nums if nums.notna().all() else None


def compute_series(df, x, y, group=None, ratio_to=None, ratio_mode="speedup", categories=None):
    """{label: (xs, ys)} as plotted: rows grouped by `group`, sorted by x, repeated x values
    averaged, y turned into a ratio to a baseline when `ratio_to` is given. x values are
    numbers when every one reads as a number, else category labels in order of appearance
    (`categories` fixes their order, e.g. to share it between several y columns)."""
    import numpy as np

    df = ok_rows(df)
    x = common.resolve_column(df.columns, x)
    y = common.resolve_column(df.columns, y)
    if group:
        # Several columns (a list, or "scene,broadcast.mode"): one line per combination.
        names = group if isinstance(group, (list, tuple)) else str(group).split(",")
        group = [common.resolve_column(df.columns, g.strip(), "group column") for g in names]
        group = group[0] if len(group) == 1 else group
    ys_all = df[y].map(common.to_number)
    df = df.assign(_y=ys_all)
    base_col, base_value = None, None
    if ratio_to:
        if "=" in ratio_to:
            base_col, base_value = ratio_to.split("=", 1)
            base_col = common.resolve_column(df.columns, base_col.strip(), "--ratio-to column")
            base_value = base_value.strip()
        else:
            base_col = common.resolve_column(df.columns, ratio_to, "--ratio-to column")
    if ratio_mode not in ("speedup", "fraction"):
        raise common.InputProblem(f"--ratio-mode must be speedup or fraction, not {ratio_mode}")
    df = df[df["_y"].notna()]
    xnum = _numeric(df[x])
    if xnum is None:
        categories = list(dict.fromkeys(list(categories or []) + list(df[x].astype(str))))
        df = df.assign(_x=df[x].astype(str).map(categories.index).astype(float))
    else:
        categories = None
        df = df.assign(_x=xnum)
    out = {}
    for label, g in groups_in_value_order(df, group):
        # Repeated x values are averaged first; the ratio is of the averages.
        agg = g.groupby("_x", sort=True)["_y"].mean().astype(float)
        xs = np.array(agg.index, dtype=float)
        ys = np.array(agg.values, dtype=float)
        if base_col is not None and base_value is not None:
            want = common.to_number(base_value)
            col = g[base_col]
            nums = col.map(common.to_number)
            match = (nums == want) if want is not None else (col.astype(str) == base_value)
            if not match.any():
                print(f"sweep_plot: group {label}: no row with {base_col} = {base_value}; "
                      "left out", file=sys.stderr)
                continue
            baseline = float(g.loc[match, "_y"].astype(float).mean())
            ys = baseline / ys if ratio_mode == "speedup" else ys / baseline
        elif base_col is not None:
            g = g.assign(_b=g[base_col].map(common.to_number).astype(float))
            baseline = g.groupby("_x", sort=True)["_b"].mean().to_numpy(float)
            ys = baseline / ys if ratio_mode == "speedup" else ys / baseline
        out[label] = (xs, ys)
    return out, categories


def groups_in_value_order(df, group):
    """[(label, rows)] per value of the group column(s), "all" without one; labels "a, b" for
    several columns, in the order of their values ("250 ns" before "1000 ns")."""
    if not group:
        return [("all", df)]
    groups = []
    for label, g in df.groupby(group, sort=False, dropna=False):
        text = ", ".join(map(str, label)) if isinstance(label, tuple) else str(label)
        groups.append((text, g))
    return sorted(groups, key=lambda item: common.value_order_key(item[0]))


def _module_figure(column):
    """(module or class, figure) of a per-module column: modules.host.utilization -> (host,
    utilization); module_classes.node*.utilization.mean -> (node* (mean), utilization); else
    None."""
    parts = str(column).split(".")
    if len(parts) >= 3 and parts[0] == "modules":
        return ".".join(parts[1:-1]), parts[-1]
    if len(parts) >= 4 and parts[0] == "module_classes" and parts[-1] == "mean":
        return ".".join(parts[1:-2]) + " (mean)", parts[-2]
    return None


def short_names(columns):
    """What differs between dotted column names: modules.host.utilization and
    modules.peripheral.pipeline.utilization -> host, peripheral.pipeline (and the common
    pattern modules.*.utilization); a class's mean, module_classes.node*.utilization.mean, is
    node* (mean) among them."""
    figures = [_module_figure(c) for c in columns]
    if len(columns) > 1 and all(figures) and len({f for _, f in figures}) == 1:
        return [m for m, _ in figures], f"modules.*.{figures[0][1]}"
    parts = [str(c).split(".") for c in columns]
    if len(parts) < 2:
        return [str(c) for c in columns], None
    head = 0
    while all(len(p) > head + 1 for p in parts) and len({p[head] for p in parts}) == 1:
        head += 1
    tail = 0
    while (all(len(p) > head + tail + 1 for p in parts)
           and len({p[len(p) - 1 - tail] for p in parts}) == 1):
        tail += 1
    short = [".".join(p[head:len(p) - tail]) for p in parts]
    if head == 0 and tail == 0:
        return short, None
    pattern = ".".join(parts[0][:head] + ["*"] + parts[0][len(parts[0]) - tail:])
    return short, pattern


def compute_multi(df, x, ys, group=None, ratio_to=None, ratio_mode="speedup"):
    """compute_series for several y columns: {label: (xs, ys)}, one entry per column and group
    ("GROUP: COLUMN" with several groups), categories shared."""
    if len(ys) == 1:
        return compute_series(df, x, ys[0], group, ratio_to, ratio_mode)
    ok = ok_rows(df)
    xcol = common.resolve_column(ok.columns, x)
    categories = None
    if _numeric(ok[xcol]) is None:
        categories = list(dict.fromkeys(ok[xcol].astype(str)))
    short, _ = short_names(ys)
    out = {}
    for y, name in zip(ys, short):
        series, categories = compute_series(df, x, y, group, ratio_to, ratio_mode, categories)
        for label, s in series.items():
            out[name if label == "all" else f"{label}: {name}"] = s
    return out, categories


def parse_bands(bands, ys):
    """{y: (low, high)} from --band Y=LOW,HIGH values; Y must be one of the --y columns."""
    out = {}
    for text in bands or []:
        y, sep, rest = text.partition("=")
        low, comma, high = rest.partition(",")
        if not sep or not comma or not y or not low or not high:
            raise common.InputProblem(f"--band {text}: expected Y=LOW,HIGH (three columns)")
        if y not in ys:
            raise common.InputProblem(f"--band {text}: {y} is not one of the --y columns")
        out[y] = (low, high)
    return out


def compute_bands(df, x, ys, bands, group=None, categories=None):
    """{label: (xs, lows, highs)} for the --y columns with a band, labelled as compute_multi
    labels their lines."""
    short = short_names(ys)[0] if len(ys) > 1 else [None]
    out = {}
    for y, name in zip(ys, short):
        if y not in bands:
            continue
        low, _ = compute_series(df, x, bands[y][0], group, categories=categories)
        high, _ = compute_series(df, x, bands[y][1], group, categories=categories)
        for label, (xs, lo) in low.items():
            if label not in high or list(high[label][0]) != list(xs):
                continue
            key = label if name is None else (name if label == "all" else f"{label}: {name}")
            out[key] = (xs, lo, high[label][1])
    return out


def time_axes(df, args, categories):
    """(x is a time, y is a time): x when it has numbers and its column is named in seconds
    or its values are written in seconds ("250 ns"); y when every --y column is named in
    seconds and no ratio is drawn."""
    ok = ok_rows(df)
    x = common.resolve_column(ok.columns, args.x)
    x_time = not categories and (common.seconds_column(x)
                                 or common.written_in_seconds(ok[x].dropna()))
    y_time = not args.ratio_to and all(common.seconds_column(y) for y in args.y)
    return bool(x_time), bool(y_time)


def scale_times(series, x_time, y_time, bands=None):
    """The series in one time unit per time axis: ({label: (xs, ys)}, x unit, y unit), a unit
    None for an axis that is not a time; with `bands` ({label: (xs, lows, highs)}) also those,
    in the same units, as a fourth value."""
    import numpy as np

    def unit_for(values):
        finite = [abs(v) for v in values if np.isfinite(v)]
        return common.time_unit(max(finite) if finite else 1.0)

    xscale, xunit = unit_for([x for xs, _ in series.values() for x in xs]) if x_time else (1, None)
    yscale, yunit = unit_for([y for _, ys in series.values() for y in ys]) if y_time else (1, None)
    scaled = {k: (np.asarray(xs) * xscale, np.asarray(ys) * yscale)
              for k, (xs, ys) in series.items()}
    if bands is None:
        return scaled, xunit, yunit
    scaled_bands = {k: (np.asarray(xs) * xscale, np.asarray(lo) * yscale, np.asarray(hi) * yscale)
                    for k, (xs, lo, hi) in bands.items()}
    return scaled, xunit, yunit, scaled_bands


def y_label(args, unit):
    """--ylabel, or the column(s) and the ratio drawn; with the time unit if y is a time."""
    if args.ylabel:
        label = args.ylabel
    else:
        y = args.y[0] if len(args.y) == 1 else short_names(args.y)[1] or ", ".join(args.y)
        if args.ratio_to:
            label = (f"speed-up over {args.ratio_to}\n({y})" if args.ratio_mode == "speedup"
                     else f"{y}\nrelative to {args.ratio_to}")
        else:
            label = y
    return common.label_with_unit(label, unit) if unit else label


def x_label(args, unit):
    """--xlabel or the column; with the time unit if x is a time."""
    label = args.xlabel or args.x
    return common.label_with_unit(label, unit) if unit else label


def format_x(ax, series, categories, logx):
    """Category names, or the values swept (up to 12) on a log axis, or readable log ticks,
    or whole numbers when every x is one."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    xs = [float(x) for xs, _ in series.values() for x in xs]
    if categories:
        ax.set_xticks(range(len(categories)))
        ax.set_xticklabels(categories, rotation=30, ha="right")
    elif logx:
        ax.set_xscale("log")
        ticks = sorted({x for x in xs if x > 0})
        if 0 < len(ticks) <= 12:
            ax.xaxis.set_major_locator(FixedLocator(ticks))
            ax.xaxis.set_minor_locator(NullLocator())
            ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: common.plain_number(v)))
        else:
            common.log_axis(ax.xaxis, integer=common.integer_valued(xs))
    elif common.integer_valued(xs):
        common.integer_axis(ax.xaxis)


def format_y(ax, series, logy):
    """Readable log ticks, or whole numbers when every y is one."""
    ys = [float(y) for _, ys in series.values() for y in ys]
    if logy:
        ax.set_yscale("log")
        common.log_axis(ax.yaxis, integer=common.integer_valued(ys))
    elif common.integer_valued(ys):
        common.integer_axis(ax.yaxis)


# One marker a line, so that lines that cross or coincide stay apart in the legend.
_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "*")


def draw(series, categories, args, bands=None):
    """(fig, ax): one line per series, times in one unit per axis, the legend off the lines,
    a series' band ({label: (xs, lows, highs)}) shaded in its colour.
    args is the parsed command line with group_used, x_time and y_time set (see figure)."""
    plt = common.pyplot()
    series, xunit, yunit, bands = scale_times(series, args.x_time, args.y_time, bands or {})
    fig, ax = plt.subplots(figsize=(7, 4.5))
    drawn = []
    for i, (label, (xs, ys)) in enumerate(series.items()):
        # A line equal to one drawn before would hide it: it is drawn dashed over it, with its
        # own marker, and its legend entry says which line it equals.
        same = next((other for other, oxs, oys in drawn
                     if list(oxs) == list(xs) and list(oys) == list(ys)), None)
        (line,) = ax.plot(xs, ys, marker=_MARKERS[i % len(_MARKERS)], markersize=4,
                          linestyle="--" if same is not None else "-",
                          label=label if same is None else f"{label} (= {same})")
        if label in bands:
            bxs, lo, hi = bands[label]
            ax.fill_between(bxs, lo, hi, color=line.get_color(), alpha=0.2, linewidth=0)
        drawn.append((label, xs, ys))
    format_x(ax, series, categories, args.logx)
    format_y(ax, series, args.logy)
    ax.set_xlabel(x_label(args, xunit))
    ax.set_ylabel(y_label(args, yunit))
    if args.title:
        ax.set_title(args.title)
    ax.grid(True, which="both", alpha=0.3)
    if list(series) != ["all"]:
        title = ", ".join(str(args.group_used).split(",")) if args.group_used else None
        common.place_legend(ax, title=title, fontsize="small" if len(series) <= 4 else "x-small")
    return fig, ax


def parse_args(argv):
    ap = argparse.ArgumentParser(
        prog="sweep_plot.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help="results.csv, results.jsonl, or the sweep's folder")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--x", required=True, help="column on the horizontal axis (a swept parameter)")
    ap.add_argument("--y", required=True, action="append",
                    help="column to plot (a stat: simulated_time_s, ...); repeat for several")
    ap.add_argument("--group", default=None,
                    help="one line per value of this column, or per combination of several "
                         "(COL,COL) (default: scene, else machine, whichever varies; 'none' for "
                         "one line)")
    ap.add_argument("--logx", action="store_true", help="logarithmic x axis")
    ap.add_argument("--logy", action="store_true", help="logarithmic y axis")
    ap.add_argument("--ratio-to", default=None, metavar="COL=VALUE|COL",
                    help="plot y relative to a baseline row (COL=VALUE, per group) or column")
    ap.add_argument("--ratio-mode", default="speedup", choices=("speedup", "fraction"),
                    help="speedup: baseline / y (default); fraction: y / baseline")
    ap.add_argument("--band", action="append", metavar="Y=LOW,HIGH",
                    help="shade the range from column LOW to column HIGH around the line of --y "
                         "column Y (a class's min..max around its mean); repeatable")
    ap.add_argument("--title", default=None)
    ap.add_argument("--xlabel", default=None)
    ap.add_argument("--ylabel", default=None)
    return ap.parse_args(argv)


def figure(args):
    """(fig, ax) of the plot the parsed command line asks for, read from its input."""
    df = read_results(args.input)
    if df.empty:
        raise common.InputProblem(f"{args.input}: the table has no rows")
    group = args.group
    if group is None:
        group = default_group(df)
    elif group.lower() == "none":
        group = None
    args.group_used = group
    bands = parse_bands(args.band, args.y)
    if bands and args.ratio_to:
        raise common.InputProblem("--band draws ranges of the columns themselves: not with "
                                  "--ratio-to")
    series, categories = compute_multi(df, args.x, args.y, group, args.ratio_to, args.ratio_mode)
    if not series or all(len(xs) == 0 for xs, _ in series.values()):
        raise common.InputProblem(
            f"{args.input}: no successful rows with a value of {' or '.join(args.y)}")
    args.x_time, args.y_time = time_axes(df, args, categories)
    band_series = compute_bands(df, args.x, args.y, bands, group, categories) if bands else {}
    return draw(series, categories, args, band_series)


def main(argv):
    args = parse_args(argv)
    fig, _ = figure(args)
    common.save(fig, args.out)
    common.pyplot().close(fig)
    return common.EXIT_OK


if __name__ == "__main__":
    common.main_wrapper(main)
