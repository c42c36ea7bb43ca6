#!/usr/bin/python3
"""Whether ullner-array's sampled runs can be scaled up to the full frame (docs/sampling.md,
"ullner-array: why a sample of rows cannot be scaled up").

Runs ullner-array (default 8 x 8 array) at 128 x 128 with `--image none` on three scenes, the
full frame and `--sample K` for K = 2, 4, 8, 16, and prints the Markdown table: the systematic
estimate's error against the full frame, K times the sampled compute time over the full frame's
("scaled compute"), and the error of two ways to scale the sample up by the work the functional
twin counts (intersection tests): their ratio, and a line through the runs at K and 2K.

    /usr/bin/python3 bench/array_sample_scaling.py [--rtsim build/rtsim] [--size 128]

Each run takes under a second; the simulated figures are deterministic, so one run each is enough.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

SCENES = ["ullner-cubes", "ullner-random-1000", "ullner-sheets-1000"]
EVERY = [2, 4, 8, 16]


def run(rtsim, scene, size, every, out):
    cmd = [rtsim, "run", "--machine", "ullner-array", "--scene", "builtin:" + scene,
           "--width", str(size), "--height", str(size), "--image", "none", "-q", "--out", out]
    if every > 1:
        cmd += ["--sample", str(every)]
    done = subprocess.run(cmd, check=False, stdout=subprocess.DEVNULL)
    if done.returncode != 0:
        # rtsim has said why on stderr (a bad --size, say).
        raise SystemExit(2)
    with open(os.path.join(out, "stats.json"), encoding="utf-8") as f:
        d = json.load(f)
    frame = d.get("sample", {}).get("detailed_frame_s", d["simulated_time_s"])
    compute = d["array"]["compute_time_s"]
    return {"frame": frame, "estimate": d["simulated_time_s"], "compute": compute,
            # The load and the readout: the same whatever the sample.
            "fixed": frame - compute, "tests": d["intersection_tests"]}


def pct(x, ref):
    return f"{100.0 * (x / ref - 1.0):+.1f}%"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rtsim", default="build/rtsim")
    ap.add_argument("--size", type=int, default=128)
    args = ap.parse_args()
    if not os.access(args.rtsim, os.X_OK):
        print(f"array_sample_scaling.py: {args.rtsim}: not an executable rtsim (--rtsim PATH)",
              file=sys.stderr)
        return 2
    print("| scene (full frame) | K | systematic estimate | scaled compute | work ratio | "
          "two densities |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            r = {k: run(args.rtsim, scene, args.size, k, os.path.join(tmp, f"{scene}-{k}"))
                 for k in [1] + EVERY}
            full = r[1]
            for i, k in enumerate(EVERY):
                s = r[k]
                ratio = s["fixed"] + s["compute"] * full["tests"] / s["tests"]
                line = ""
                if 2 * k in r:
                    t = r[2 * k]
                    slope = (s["compute"] - t["compute"]) / (s["tests"] - t["tests"])
                    line = pct(s["fixed"] + s["compute"] + slope * (full["tests"] - s["tests"]),
                               full["frame"])
                label = f"{scene} ({full['frame']:.4f} s)" if i == 0 else ""
                print(f"| {label} | {k} | {pct(s['estimate'], full['frame'])} | "
                      f"{k * s['compute'] / full['compute']:.3f} | "
                      f"{pct(ratio, full['frame'])} | {line} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
