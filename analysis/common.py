"""Helpers shared by the analysis scripts: reading rtsim's outputs, flattening JSON into
dotted column names, choosing time units, and drawing with matplotlib's Agg backend (no
display needed). Only Debian's python3-matplotlib, python3-numpy and python3-pandas."""

import difflib
import json
import math
import os
import sys

# Exit statuses, as rtsim's: 0 success, 1 failure, 2 bad input or usage.
EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


class InputProblem(Exception):
    """Bad input: the message names the file and what was expected."""


def pyplot():
    """matplotlib.pyplot on the Agg backend (import late: --help works without matplotlib)."""
    import matplotlib

    matplotlib.use("Agg")
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


def time_unit(max_seconds):
    """(scale, label) so that max_seconds * scale reads well: s, ms, us or ns."""
    for scale, label in ((1.0, "s"), (1e3, "ms"), (1e6, "µs"), (1e9, "ns")):
        if max_seconds * scale >= 1.0:
            return scale, label
    return 1e9, "ns"


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
