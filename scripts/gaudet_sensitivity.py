#!/usr/bin/env python3
"""Sensitivity of Fig. 6-10's ShellProcessor latencies to gaudet-pert's open assumptions.

The thesis does not say how many rays a ShellProcessor holds at once or how many ID registers
its BIC has (seed 001 L910, L1060), and a model may or may not stream packets into the BIC's
FIFOs (L920, L924) or keep the root packet in local memory (L662, L863). This runs
`rtsim run --machine gaudet-pert` on builtin:npp-212, -412 and -812 (binary, quad and oct trees,
1 PERT, adaptive, breadth-first) at each setting, with every one of those parameters given on
the command line so the table does not depend on the defaults, and prints the ShellProcessor's
latency per ray (gaudet.shell.latency_per_ray_s) and its starvation (starved_per_ray_s: waiting
for a packet with a ray slot free and no ray come, which is not latency). Every image is
compared byte for byte with `rtsim render --machine gaudet-pert` on the same scene and size.

    scripts/gaudet_sensitivity.py build/rtsim                 # the table (Markdown), 40x40
    scripts/gaudet_sensitivity.py build/rtsim --orders        # and Fig. 6-11's orders, 404..420
    scripts/gaudet_sensitivity.py build/rtsim --json out.json

Exits 1 if any image differs from the functional render's.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

TREES = ["212", "412", "812"]
THESIS = {"212": 124.9, "412": 5.0, "812": 0.5}  # seed 001 L1025-L1030, us per ray
ORDER_SCENES = ["404", "408", "412", "416", "420"]
THESIS_ORDERS = {"breadth": "4.7-5.1", "depth": "11.4-12.1", "random": "11.3-12.0"}  # L1032-L1039

# (label, stream, root_local, rays_in_flight, id_registers)
SETTINGS = [
    ("whole packets, 4 rays in flight, 8 ID registers (main before issue 12)", "false", "false", 4, 8),
    ("streaming only, 4 rays in flight", "true", "false", 4, 8),
    ("streaming only, 2 rays in flight", "true", "false", 2, 8),
    ("streaming + root local, 1 ray, 2 ID registers", "true", "true", 1, 2),
    ("streaming + root local, 1 ray, 1 ID register", "true", "true", 1, 1),
]


def setting_args(stream, root_local, rays, ids):
    return ["-p", f"pert.shell.bic.stream={stream}", "-p", f"pert.shell.root_local={root_local}",
            "-p", f"pert.shell.rays_in_flight={rays}", "-p", f"pert.shell.bic.id_registers={ids}"]


def run(rtsim, command, scene, size, out, extra):
    args = [rtsim, command, "--machine", "gaudet-pert", "--scene", f"builtin:npp-{scene}",
            "--width", str(size), "--height", str(size), "-q", "--out", out] + extra
    r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"failed ({r.returncode}): {' '.join(args)}\n{r.stdout}")


def read(path):
    with open(path, "rb") as f:
        return f.read()


def measure(rtsim, tmp, renders, scene, size, extra, tag):
    out = os.path.join(tmp, tag)
    run(rtsim, "run", scene, size, out, extra)
    with open(os.path.join(out, "stats.json")) as f:
        shell = json.load(f)["gaudet"]["shell"]
    if scene not in renders:
        ref = os.path.join(tmp, f"render-{scene}")
        run(rtsim, "render", scene, size, ref, [])
        renders[scene] = read(os.path.join(ref, "image.png"))
    return {"latency_us": shell["latency_per_ray_s"] * 1e6,
            "starved_us": shell["starved_per_ray_s"] * 1e6,
            "processing_us": shell["processing_per_ray_s"] * 1e6,
            "image_identical": read(os.path.join(out, "image.png")) == renders[scene]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("rtsim", nargs="?", default="build/rtsim")
    ap.add_argument("--size", type=int, default=40, help="image side (default 40)")
    ap.add_argument("--orders", action="store_true",
                    help="also breadth/depth/random on 404..420 at the 1-ray settings")
    ap.add_argument("--json", help="write every measurement here")
    a = ap.parse_args()
    rtsim = os.path.abspath(a.rtsim)
    results = {"size": a.size, "settings": [], "orders": []}
    renders = {}
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for label, stream, root_local, rays, ids in SETTINGS:
            extra = setting_args(stream, root_local, rays, ids)
            row = {"setting": label, "params": extra[1::2], "trees": {}}
            for s in TREES:
                row["trees"][s] = measure(rtsim, tmp, renders, s, a.size, extra, f"{len(results['settings'])}-{s}")
                ok &= row["trees"][s]["image_identical"]
            results["settings"].append(row)
        if a.orders:
            for label, stream, root_local, rays, ids in SETTINGS:
                if rays != 1:
                    continue
                row = {"setting": label, "orders": {}}
                for order in ("breadth", "depth", "random"):
                    extra = setting_args(stream, root_local, rays, ids) + ["-p", f"broadcast.order={order}"]
                    row["orders"][order] = []
                    for s in ORDER_SCENES:
                        m = measure(rtsim, tmp, renders, s, a.size, extra, f"o-{ids}-{order}-{s}")
                        ok &= m["image_identical"]
                        row["orders"][order].append(m["latency_us"])
                results["orders"].append(row)

    print(f"ShellProcessor latency per ray (us), {a.size}x{a.size}, 1 PERT, adaptive, breadth-first;"
          " in brackets latency + starved")
    print()
    print("| setting | 212 | 412 | 812 | images |")
    print("|---|---|---|---|---|")
    print("| thesis (Fig. 6-10) | " + " | ".join(f"{THESIS[s]}" for s in TREES) + " | |")
    for row in results["settings"]:
        cells = [f"{t['latency_us']:.3g} ({t['latency_us'] + t['starved_us']:.3g})"
                 for t in row["trees"].values()]
        same = all(t["image_identical"] for t in row["trees"].values())
        print(f"| {row['setting']} | " + " | ".join(cells) + f" | {'identical' if same else 'DIFFER'} |")
    if results["orders"]:
        print()
        print("Fig. 6-11: latency per ray (us) on 404/408/412/416/420 by broadcast order")
        print()
        print("| setting | breadth | depth | random |")
        print("|---|---|---|---|")
        print("| thesis | " + " | ".join(THESIS_ORDERS[o] for o in ("breadth", "depth", "random")) + " |")
        for row in results["orders"]:
            print(f"| {row['setting']} | " + " | ".join(
                "/".join(f"{v:.2f}" for v in row["orders"][o]) for o in ("breadth", "depth", "random"))
                + " |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    if not ok:
        print("\nsome image differs from rtsim render --machine gaudet-pert", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
