"""Helpers shared by the analysis scripts: reading rtsim's outputs, flattening JSON into
dotted column names, reading numbers written with units, and drawing with matplotlib's Agg
backend (no display needed) so that every axis reads the same way: a time axis in one unit
(ns, µs, ms, s or h) named in its label, log axes with several labelled ticks, whole numbers on
axes of counts, no offset or multiplier text, legends in the order of their values and off the
data. Only Debian's python3-matplotlib, python3-numpy and python3-pandas."""

import difflib
import json
import math
import os
import re
import sys

# Exit statuses, as rtsim's: 0 success, 1 failure, 2 bad input or usage.
EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


class InputProblem(Exception):
    """Bad input: the message names the file and what was expected."""


def pyplot():
    """matplotlib.pyplot on the Agg backend (import late: --help works without matplotlib).
    Linear axes label their ticks in full: no offset ("1e-6+8.804e-2") and no multiplier."""
    import matplotlib

    matplotlib.use("Agg")
    matplotlib.rcParams["axes.formatter.useoffset"] = False
    matplotlib.rcParams["axes.formatter.limits"] = (-100, 100)  # never scientific notation
    import matplotlib.pyplot as plt

    return plt


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise InputProblem(f"{path}: cannot read: {e.strerror}")
    except json.JSONDecodeError as e:
        raise InputProblem(f"{path}:{e.lineno}: not JSON: {e.msg}")


def read_stats(path):
    """stats.json of a run, given the file or the run's folder: (path read, the object)."""
    if os.path.isdir(path):
        path = os.path.join(path, "stats.json")
    stats = read_json(path)
    if not isinstance(stats, dict):
        raise InputProblem(f"{path}: expected a JSON object (stats.json)")
    return path, stats


def flatten(obj, prefix="", out=None):
    """{"a": {"b": 1}} -> {"a.b": 1}. Lists are kept as values."""
    if out is None:
        out = {}
    for k, v in obj.items():
        if isinstance(v, dict):
            flatten(v, f"{prefix}{k}.", out)
        else:
            out[f"{prefix}{k}"] = v
    return out


def spelling_variants(name):
    """A column name and its other spelling (utilisation / utilization)."""
    variants = [name]
    for a, b in (("utilisation", "utilization"), ("utilization", "utilisation")):
        if a in name:
            variants.append(name.replace(a, b))
    return variants


def resolve_column(columns, name, what="column"):
    """The column called `name` (or its other spelling); InputProblem with suggestions."""
    columns = list(columns)
    for v in spelling_variants(name):
        if v in columns:
            return v
    close = difflib.get_close_matches(name, [str(c) for c in columns], n=4, cutoff=0.5)
    hint = f"; did you mean {', '.join(close)}?" if close else ""
    raise InputProblem(f"no {what} '{name}'{hint} (columns: {', '.join(map(str, columns))})")


# ---- Numbers written with units ------------------------------------------------------------

# SI prefixes of values written with units in configs and sweep files ("400 ns", "5 MHz").
_PREFIX = {"p": 1e-12, "n": 1e-9, "u": 1e-6, "µ": 1e-6, "m": 1e-3, "": 1.0, "k": 1e3,
           "K": 1e3, "M": 1e6, "G": 1e9, "T": 1e12}
_UNIT_RE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([pnuµmkKMGT]?)"
                      r"(s|Hz|bit/s|bps|bit|B|)\s*$")


def _number_and_unit(value):
    """(float, base unit) for 3 (3.0, ""), "400 ns" (4e-7, "s"), "5 MHz" (5e6, "Hz"); None if
    it is not a number."""
    if isinstance(value, bool):
        return float(value), ""
    if isinstance(value, (int, float)):
        return float(value), ""
    if isinstance(value, str):
        m = _UNIT_RE.match(value)
        if m:
            number, prefix, unit = m.groups()
            if unit == "" and prefix != "":
                return None  # "3 m" is not a unit rtsim writes
            return float(number) * _PREFIX[prefix], unit
    return None


def to_number(value):
    """A float for 3, "3", "400 ns" (4e-7), "5 MHz" (5e6); None if it is not a number."""
    parsed = _number_and_unit(value)
    return parsed[0] if parsed else None


def written_in_seconds(values):
    """Whether every value is a time written with its unit ("250 ns", "1 us")."""
    units = [_number_and_unit(v) for v in values]
    return bool(units) and all(u is not None and u[1] == "s" for u in units)


def seconds_column(name):
    """Whether a column holds seconds by its name, as rtsim names them: simulated_time_s,
    ray_latency_s.mean."""
    name = str(name)
    return name.endswith("_s") or "_s." in name


# ---- Axes --------------------------------------------------------------------------------------

# Units of a time axis, largest first: (unit, scale from seconds).
_TIME_UNITS = (("h", 1.0 / 3600.0), ("s", 1.0), ("ms", 1e3), ("µs", 1e6), ("ns", 1e9))


def time_unit(max_seconds):
    """(scale, unit) for a time axis reaching max_seconds: the largest of h, s, ms, µs and ns
    in which it reads 1 or more; seconds * scale are the values to draw."""
    for unit, scale in _TIME_UNITS:
        if abs(max_seconds) * scale >= 1.0:
            return scale, unit
    return 1e9, "ns"


def seconds_text(seconds):
    """A time as text in the unit that suits it, 4 significant digits: "2.627 ms", "0 s"."""
    if seconds == 0 or not math.isfinite(seconds):
        return f"{seconds:g} s"
    scale, unit = time_unit(abs(seconds))
    return f"{seconds * scale:.4g} {unit}"


def instance_pattern(name):
    """A module's class name: its numbers as "*" ("pert3.shell" -> "pert*.shell")."""
    return re.sub(r"\d+", "*", str(name))


def label_with_unit(label, unit):
    """The axis label naming `unit`: a "(s)" in it becomes "(unit)", else " (unit)" is
    appended."""
    if "(s)" in label:
        return label.replace("(s)", f"({unit})")
    return f"{label} ({unit})"


def plain_number(value):
    """A tick label without exponent: 0.0001, 20, 1500000 (6 significant digits)."""
    text = f"{value:.6g}"
    if "e" in text:
        import numpy as np

        text = np.format_float_positional(float(text), trim="-")
    return text


def integer_valued(values):
    """Whether every finite value is a whole number (counts, indices)."""
    import numpy as np

    v = np.asarray(list(values), dtype=float)
    v = v[np.isfinite(v)]
    return len(v) > 0 and bool(np.all(v == np.round(v)))


def integer_axis(axis):
    """Ticks only at whole numbers on a linear axis of counts or indices."""
    from matplotlib.ticker import MaxNLocator

    axis.set_major_locator(MaxNLocator(nbins="auto", steps=[1, 2, 2.5, 5, 10], integer=True))


# Mantissas of the ticks of a logarithmic axis, densest first.
_LOG_MANTISSAS = (tuple(range(1, 10)), (1, 2, 3, 5), (1, 2, 5), (1,))


def log_ticks(vmin, vmax, integer=False, most=8):
    """Labelled ticks of a logarithmic axis over [vmin, vmax], from the tick at or below vmin
    to the tick at or above vmax: the densest of 1..9, 1-2-3-5, 1-2-5 a decade, or decades,
    that gives 3 to `most` ticks, 2 of them within [vmin, vmax], and at most doubles the
    range's span; else (a range under a decade) evenly spaced ticks, whole numbers if
    `integer`."""
    import numpy as np
    from matplotlib.ticker import MaxNLocator

    vmin, vmax = sorted((vmin, vmax))
    if vmax <= 0:
        return np.array([1.0, 10.0])
    vmin = vmin if vmin > 0 else vmax / 1e3
    tol = 1e-9
    if vmax <= vmin * (1 + tol):  # one value: a factor of 2 either side
        vmin, vmax = vmin / 2.0, vmax * 2.0
    first, last = math.floor(math.log10(vmin) + tol), math.ceil(math.log10(vmax) - tol)
    for mantissas in _LOG_MANTISSAS:
        stride = 1
        if len(mantissas) == 1:
            stride = max(1, math.ceil((last - first) / (most - 1)))
        every = np.array([m * 10.0 ** d for d in range(first - stride, last + stride + 1,
                                                       stride) for m in mantissas])
        ticks = _bracket(every, vmin, vmax, tol)
        inside = (ticks >= vmin * (1 - tol)) & (ticks <= vmax * (1 + tol))
        widened = math.log(ticks[-1] / ticks[0]) / max(math.log(vmax / vmin), 1e-12)
        if 3 <= len(ticks) <= most and np.count_nonzero(inside) >= 2 and widened <= 2.0:
            return ticks
    if vmax >= 10 * vmin:
        return ticks  # decades
    even = MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10], integer=integer).tick_values(vmin, vmax)
    return _bracket(even[even > 0], vmin, vmax, tol)


def _bracket(ticks, vmin, vmax, tol):
    """The sorted ticks from the last at or below vmin to the first at or above vmax."""
    import numpy as np

    ticks = np.unique(ticks)
    below = ticks[ticks <= vmin * (1 + tol)]
    above = ticks[ticks >= vmax * (1 - tol)]
    lo = below[-1] if len(below) else ticks[0]
    hi = above[0] if len(above) else ticks[-1]
    return ticks[(ticks >= lo) & (ticks <= hi)]


def log_axis(axis, integer=False):
    """Readable ticks on a logarithmic axis (call after set_xscale/set_yscale("log")): the
    ticks of log_ticks labelled as plain numbers, and an autoscaled view that reaches the
    ticks on either side of the data."""
    from matplotlib.ticker import FuncFormatter, Locator, NullFormatter

    class ReadableLogLocator(Locator):
        def __call__(self):
            return self.tick_values(*self.axis.get_view_interval())

        def tick_values(self, vmin, vmax):
            return log_ticks(vmin, vmax, integer, self.most())

        def view_limits(self, vmin, vmax):
            """The autoscaled view (data and margins) widened to the ticks around the data."""
            lo, hi = sorted(self.axis.get_data_interval())
            if not (0 < lo <= hi < math.inf):
                lo, hi = vmin, vmax
            ticks = log_ticks(lo, hi, integer, self.most())
            return min(ticks[0], vmin), max(ticks[-1], vmax)

        def most(self):
            """As many labels as the axis has room for, 4 to 12."""
            room = self.axis.get_tick_space() if self.axis is not None else 8
            return min(max(int(room), 4), 12)

    axis.set_major_locator(ReadableLogLocator())
    axis.set_major_formatter(FuncFormatter(lambda v, _: plain_number(v)))
    axis.set_minor_formatter(NullFormatter())
    # The view may already be autoscaled with the old locator: scale it again with this one.
    axis.axes.autoscale_view(scalex=axis.axis_name == "x", scaley=axis.axis_name == "y")


# ---- Legends -------------------------------------------------------------------------------

# Free space kept between a legend inside the axes and the data (pixels).
_LEGEND_CLEARANCE_PX = 4.0
# A legend that does not fit inside goes beside the axes with at most this many entries, else
# below them in columns.
_LEGEND_BESIDE_MAX = 6
# Places tried inside the axes, in order, before the legend goes beside them.
_LEGEND_INSIDE = ("upper right", "upper left", "lower right", "lower left", "center right",
                  "center left", "upper center", "lower center")


def value_order_key(label):
    """Sort key putting legend labels in the order of their values: "250 ns" < "500 ns" <
    "1000 ns" < "2 us". Parts of a label joined by ", " or ": " compare in turn; numbers
    (with units) before text; text in natural order (npp-8 before npp-16)."""
    key = []
    for part in re.split(r", |: ", str(label)):
        number = to_number(part)
        if number is not None:
            key.append((0, number, ()))
        else:
            chunks = tuple((0, int(c), "") if c.isdigit() else (1, 0, c)
                           for c in re.split(r"(\d+)", part) if c)
            key.append((1, 0.0, chunks))
    return tuple(key)


def place_legend(ax, **kwargs):
    """ax.legend(**kwargs) in the first place inside the axes where it hides no data of the
    figure, else beside the axes on the right, or below them in columns if it has more than
    _LEGEND_BESIDE_MAX entries and no other axes lies below. Call when the data and limits are
    final."""
    for a in ax.figure.axes:  # autoscale now: matplotlib does it lazily, at the next draw
        a.get_xlim()
        a.get_ylim()
    renderer = ax.figure.canvas.get_renderer()
    for loc in _LEGEND_INSIDE:
        legend = ax.legend(loc=loc, **kwargs)
        box = legend.get_window_extent(renderer).padded(_LEGEND_CLEARANCE_PX)
        if not covers_data(ax.figure, box, renderer):
            return legend
    handles, _ = ax.get_legend_handles_labels()
    below_is_free = not any(other is not ax and other.bbox.y1 <= ax.bbox.y0 + 1.0
                            for other in ax.figure.axes)
    if len(handles) > _LEGEND_BESIDE_MAX and below_is_free:
        # Many entries beside the axes would widen the figure by the legend's width: below the
        # axes (the lowest of the figure) in columns instead, as wide as the axes allow.
        axis_box = ax.xaxis.get_tightbbox(renderer)
        under = (axis_box.y0 if axis_box is not None else ax.bbox.y0) - _LEGEND_CLEARANCE_PX
        y = ax.transAxes.inverted().transform((0.0, under))[1]
        kwargs.setdefault("ncol", min(4, len(handles)))
        return ax.legend(loc="upper center", bbox_to_anchor=(0.5, y), borderaxespad=0.0,
                         **kwargs)
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                     **kwargs)


def covers_data(fig, box, renderer):
    """Whether the box (display pixels) hides a line, marker, bar, patch, collection or text
    of an axes of the figure. Artists below zorder 1 (background shading) do not count."""
    for ax in fig.axes:
        if not ax.bbox.overlaps(box):
            continue
        for artist in list(ax.lines) + list(ax.patches) + list(ax.collections) + list(ax.texts):
            if (artist.get_visible() and artist.get_zorder() >= 1
                    and _artist_covered(artist, box, renderer)):
                return True
    return False


def _artist_covered(artist, box, renderer):
    """Whether one artist of the axes shows inside the box."""
    from matplotlib.collections import LineCollection, PathCollection
    from matplotlib.lines import Line2D
    from matplotlib.text import Text

    if isinstance(artist, Line2D):
        return _line_covered(artist, box)
    if isinstance(artist, Text):
        return bool(artist.get_text().strip()) and artist.get_window_extent(
            renderer).overlaps(box)
    if isinstance(artist, PathCollection):  # scatter: markers at the offsets
        points = artist.get_offset_transform().transform(artist.get_offsets())
        sizes = artist.get_sizes()
        pad = (max(sizes) ** 0.5 / 2.0 if len(sizes) else 3.0) * artist.figure.dpi / 72.0
        return _points_in(points, box, pad)
    # Bars, steps, polygons and other collections: their outlines, and insides if filled.
    if hasattr(artist, "get_paths"):
        paths, filled = artist.get_paths(), not isinstance(artist, LineCollection)
    else:
        paths, filled = [artist.get_path()], artist.get_fill()
    transform = artist.get_transform()
    return any(transform.transform_path(p).intersects_bbox(box, filled=filled)
               for p in paths if len(p.vertices))


def _line_covered(line, box):
    """Whether a Line2D's segments cross the box or one of its markers lies in it."""
    path = line.get_transform().transform_path(line.get_path())
    if line.get_linestyle() not in ("None", "none", "", " ") and path.intersects_bbox(
            box, filled=False):
        return True
    if line.get_marker() not in (None, "None", "none", "", " "):
        pad = line.get_markersize() / 2.0 * line.figure.dpi / 72.0
        return _points_in(path.vertices, box, pad)
    return False


def _points_in(points, box, pad):
    """Whether any display point lies within the box grown by pad pixels."""
    import numpy as np

    p = np.asarray(points, dtype=float)
    if p.size == 0:
        return False
    inside = ((p[:, 0] >= box.x0 - pad) & (p[:, 0] <= box.x1 + pad) &
              (p[:, 1] >= box.y0 - pad) & (p[:, 1] <= box.y1 + pad))
    return bool(np.any(inside))


def finite(x):
    try:
        return x is not None and math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def save(fig, out_path, dpi=110):
    """Write the figure atomically (temporary name, then rename): no half-written PNG."""
    out_path = os.fspath(out_path)
    folder = os.path.dirname(os.path.abspath(out_path))
    os.makedirs(folder, exist_ok=True)
    tmp = os.path.join(folder, f".{os.path.basename(out_path)}.{os.getpid()}.partial")
    try:
        fig.savefig(tmp, format="png", dpi=dpi, bbox_inches="tight")
        os.replace(tmp, out_path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def main_wrapper(main):
    """Run main(argv) and turn InputProblem into one message and exit status 2."""
    try:
        sys.exit(main(sys.argv[1:]))
    except InputProblem as e:
        print(f"{os.path.basename(sys.argv[0])}: {e}", file=sys.stderr)
        sys.exit(EXIT_BAD_INPUT)
    except ImportError as e:
        print(f"{os.path.basename(sys.argv[0])}: {e} (install Debian's python3-matplotlib, "
              "python3-numpy and python3-pandas; run with /usr/bin/python3)", file=sys.stderr)
        sys.exit(EXIT_FAILURE)
