#!/usr/bin/env python3
"""Fingerprints of every machine on every scene: the image's SHA-256 and the simulated frame time.

A refactoring of the machines must leave images byte-identical and frame times equal; this runs
`rtsim run` for each machine on each scene it can hold (and `rtsim render --machine` for its
functional twin) and writes one JSON object, so that two builds can be compared:

    scripts/machine_fingerprints.py OLD_BUILD/rtsim old.json
    scripts/machine_fingerprints.py build/rtsim new.json --compare old.json

--compare prints every image that changed and every frame time that moved by more than
--rtol (default 1e-9) relative, and exits 1 if any did. A scene a machine rejects (exit 2) is
recorded as rejected; the rejection must stay the same.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SCENES = [os.path.join(HERE, "..", "..", "shared", "scenes", n)
                  for n in ("balls-s1.nff", "balls-s2.nff", "balls-s3.nff", "teapot-s2.nff",
                            "teapot.bpt", "tetra-s3.nff")] + [
    "builtin:ullner-cubes", "builtin:npp-412", "builtin:ullner-random-1000"]


def machines(rtsim):
    """Every machine the binary registers (`rtsim list machines --format json`; a binary from
    before that option: its text listing), so a new machine needs no edit here."""
    p = subprocess.run([rtsim, "list", "machines", "--format", "json"], capture_output=True,
                       text=True)
    if p.returncode == 0:
        return [m["name"] for m in json.loads(p.stdout)]
    p = subprocess.run([rtsim, "list", "machines"], capture_output=True, text=True, check=True)
    names = [line.split()[0] for line in p.stdout.splitlines() if line.startswith("  ")]
    return [n for n in names if n != "(none)"]


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def one(rtsim, command, machine, scene, size, extra):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        args = [rtsim, command, "--machine", machine, "--scene", scene, "--width", str(size),
                "--height", str(size), "-q", "--out", out] + extra
        p = subprocess.run(args, capture_output=True, text=True)
        if p.returncode != 0:
            return {"exit": p.returncode, "error": (p.stderr or p.stdout).strip()[-300:]}
        with open(os.path.join(out, "stats.json")) as f:
            stats = json.load(f)
        return {"exit": 0, "image": sha256(os.path.join(out, "image.png")),
                "simulated_time_s": stats.get("simulated_time_s"),
                "intersection_tests": stats.get("intersection_tests")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rtsim")
    ap.add_argument("out")
    ap.add_argument("--size", type=int, default=48, help="image width and height (default 48)")
    ap.add_argument("--scene", action="append", help="scenes (default: shared/scenes and three "
                    "builtins)")
    ap.add_argument("--compare", help="a JSON written earlier: report what differs")
    ap.add_argument("--rtol", type=float, default=1e-9)
    a = ap.parse_args()
    result = {}
    for machine in machines(a.rtsim):
        for scene in a.scene or DEFAULT_SCENES:
            key = machine + " " + os.path.basename(scene)
            result[key + " run"] = one(a.rtsim, "run", machine, scene, a.size, [])
            result[key + " render"] = one(a.rtsim, "render", machine, scene, a.size, [])
            print(key, result[key + " run"].get("image", result[key + " run"].get("exit")),
                  file=sys.stderr)
    with open(a.out, "w") as f:
        json.dump(result, f, indent=1, sort_keys=True)
    if not a.compare:
        return 0
    with open(a.compare) as f:
        old = json.load(f)
    bad = 0
    for key in sorted(set(old) | set(result)):
        o, n = old.get(key), result.get(key)
        if o is None or n is None or o.get("exit") != n.get("exit"):
            print(f"{key}: {o} -> {n}")
            bad += 1
            continue
        if o.get("image") != n.get("image"):
            print(f"{key}: image changed")
            bad += 1
        to, tn = o.get("simulated_time_s"), n.get("simulated_time_s")
        if to is not None and tn is not None and abs(tn - to) > a.rtol * abs(to):
            print(f"{key}: frame time {to} -> {tn} ({(tn - to) / to:+.3g})")
            bad += 1
    print(f"{len(result)} runs compared, {bad} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
