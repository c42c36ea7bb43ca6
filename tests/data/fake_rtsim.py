#!/usr/bin/python3
"""A stand-in for the rtsim binary in validate_test: answers `run` and `render` the way the
machines are specified to (docs/validation.md), with Ullner's and Gaudet's formulas, so the
validation framework (subprocesses, parallel runs, tables, JSON, CSV, exit status) can be tested
before the SystemC machines exist, and with faults injected on purpose:

  FAKE_RTSIM_FAIL=SUFFIX   runs whose --out folder ends with SUFFIX exit with status 3
  FAKE_RTSIM_SKEW=F        peripheral times per ray are multiplied by F
"""
import json
import math
import os
import sys

II = 333.333e-9     # peripheral.intersect_interval
STEP = 1e-6         # peripheral.grid.step_time
T_I, T_S = 429e-6, 710e-6


def arg(name, default=None):
    a = sys.argv
    return a[a.index(name) + 1] if name in a else default


def params():
    out = {}
    a = sys.argv
    for i, x in enumerate(a):
        if x == "-p":
            k, v = a[i + 1].split("=", 1)
            out[k] = v
    return out


def main():
    cmd = sys.argv[1]
    out = arg("--out")
    scene = arg("--scene")
    w, h = int(arg("--width", "64")), int(arg("--height", "64"))
    p = params()
    suffix = os.environ.get("FAKE_RTSIM_FAIL")
    if suffix and out.endswith(suffix):
        print("fake rtsim: failing on purpose", file=sys.stderr)
        return 3
    os.makedirs(out, exist_ok=True)
    prims = {"builtin:default": 69, "builtin:ullner-cubes": 498}.get(scene, 1000)
    lights = scene in ("builtin:default", "builtin:ullner-cubes")
    primary = w * h
    shadow = primary if lights else 0
    reflected = primary // 2 if scene == "builtin:default" else 0
    total = primary + shadow + reflected
    stats = {"command": cmd, "machine": arg("--machine", "functional"), "scene": scene,
             "width": w, "height": h,
             "wall_time_s": 0.01,
             "rays": {"total": total, "primary": primary, "shadow": shadow,
                      "reflected": reflected, "refracted": 0},
             "scene_stats": {"primitives": prims}, "params": {}}
    machine = stats["machine"]
    if cmd == "run" and machine == "vax-750":
        stats["simulated_time_s"] = total * (T_S + T_I * prims)
        stats["intersection_tests"] = total * prims
    elif cmd == "run":
        stages = 17 if p.get("peripheral.adder_stages", "1") == "1" else 33
        latency = stages * II
        n = int(p.get("peripheral.grid.divisions", "0"))
        if n == 0:
            tests, visited = prims, 1.0
        else:  # Ullner's model, seed 000 L614-L652, with d_r = 1/2 and a_t = 2
            visited = (n - 1) * 0.5 + 1
            occ = (n - 1) * math.sqrt(2.0) + 1
            tests = ((1 - 1 / n) * 0.5 / n ** 2 + 1 / occ ** 2) * prims
        per_ray = (visited * STEP if n else 0.0) + tests * II + latency
        per_ray *= float(os.environ.get("FAKE_RTSIM_SKEW", "1"))
        stats["simulated_time_s"] = total * per_ray
        stats["intersection_tests"] = round(total * tests)
        stats["params"]["peripheral.grid.step_time"] = "1 us"
        stats["peripheral"] = {
            "intersect_interval_s": II, "pipeline_latency_s": latency, "pipeline_stages": stages,
            "time_per_ray_s": per_ray, "tests_per_ray": tests,
            "dda_steps_per_ray": visited - 1, "subvolumes_visited_per_ray": visited,
            "mean_ray_travel": 0.5}
    else:
        stats["intersection_tests"] = total * 10
    with open(os.path.join(out, "stats.json"), "w") as f:
        json.dump(stats, f)
    with open(os.path.join(out, "image.png"), "w") as f:
        f.write("fake image %s %d %d\n" % (scene, w, h))
    return 0


if __name__ == "__main__":
    sys.exit(main())
