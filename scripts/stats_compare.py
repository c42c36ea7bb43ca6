#!/usr/bin/env python3
"""Every stats.json key of two builds, compared: what a refactoring removed, changed or added.

    scripts/stats_compare.py OLD_BUILD/rtsim build/rtsim [--out DIR]

Runs each registered machine's test runs (`rtsim list machines --format json`) and its sample
scene with --trace vcd --latency-probe, at 24x24, with both binaries, then compares each pair of
stats.json key by key (wall-clock keys left out) and their images. Keys are grouped with the
digits of instance names replaced by '#' (node12.link_e -> node#.link_e), so a change to every
node is one line. Prints REMOVED, CHANGED (with one example) and ADDED; exits 1 if an image or a
value changed. A renamed key shows as removed and added: list it in docs/stats.md.
"""
import argparse
import collections
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile

SKIP = {"wall_time_s", "rays_per_second", "version", "functional_wall_time_s", "overhead_ratio"}


def runs(rtsim):
    p = subprocess.run([rtsim, "list", "machines", "--format", "json"], capture_output=True,
                       text=True, check=True)
    for m in json.loads(p.stdout):
        extra = ["--scene " + m["sample_scene"] + " --trace vcd --latency-probe"]
        for i, r in enumerate(m["test_runs"] + extra):
            yield f"{m['name']}-{i}", ["--machine", m["name"]] + shlex.split(r)


def capture(rtsim, out, listed_by):
    for tag, args in runs(listed_by):
        d = os.path.join(out, tag)
        subprocess.run([rtsim, "run", "--width", "24", "--height", "24", "-q", "--out", d] + args,
                       capture_output=True)


def flat(j, p=""):
    out = {}
    if isinstance(j, dict):
        for k, v in j.items():
            out.update(flat(v, p + "/" + k if p else k))
    elif isinstance(j, list) and j and isinstance(j[0], (dict, list)):
        for i, v in enumerate(j):
            out.update(flat(v, f"{p}[{i}]"))
    else:
        out[p] = j
    return out


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--out", help="keep the runs here (default: a temporary folder)")
    a = ap.parse_args()
    root = a.out or tempfile.mkdtemp(prefix="rtsim-stats-compare-")
    old_dir, new_dir = os.path.join(root, "old"), os.path.join(root, "new")
    # The runs are the new build's list (an older build may not list its machines as JSON).
    capture(a.old, old_dir, a.new)
    capture(a.new, new_dir, a.new)
    removed, changed, added = (collections.Counter() for _ in range(3))
    example = {}
    bad = False
    for tag in sorted(os.listdir(old_dir)):
        po, pn = (os.path.join(d, tag, "stats.json") for d in (old_dir, new_dir))
        if not os.path.exists(po) or not os.path.exists(pn):
            print("missing a stats.json:", tag)
            bad = True
            continue
        if sha(os.path.join(old_dir, tag, "image.png")) != sha(os.path.join(new_dir, tag,
                                                                           "image.png")):
            print("IMAGE DIFFERS:", tag)
            bad = True
        with open(po) as f:
            o = flat(json.load(f))
        with open(pn) as f:
            n = flat(json.load(f))
        machine = tag.rsplit("-", 1)[0]
        for k, v in o.items():
            if k.split("/")[0] in SKIP:
                continue
            key = machine + " " + re.sub(r"\d+", "#", k)
            if k not in n:
                removed[key] += 1
            elif v != n[k] and not (isinstance(v, (int, float)) and isinstance(n[k], (int, float))
                                    and abs(v - n[k]) <= 1e-12 * max(abs(v), abs(n[k]))):
                changed[key] += 1
                example[key] = (tag, k, v, n[k])
                bad = True
        for k in n:
            if k.split("/")[0] not in SKIP and k not in o:
                added[machine + " " + re.sub(r"\d+", "#", k)] += 1
    for title, counter in (("REMOVED", removed), ("CHANGED", changed), ("ADDED", added)):
        print(f"== {title} ({len(counter)})")
        for k, n in sorted(counter.items()):
            print(f"  {k}  x{n}", example.get(k, ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
