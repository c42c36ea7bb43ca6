#!/usr/bin/python3
"""Tests of analysis/: each script on small inputs made here, checking the numbers it draws
(through the function that computes them) and that its PNG is a real picture. Run by CTest
(tests/CMakeLists.txt) with Debian's /usr/bin/python3; exits 77 (skipped) when matplotlib,
numpy or pandas is missing. With RTSIM_BINARY set, also one real `rtsim run` whose trace and
stats.json must give the same utilisation."""

import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))
ANALYSIS = os.path.join(os.path.dirname(HERE), "analysis")
sys.path.insert(0, ANALYSIS)

try:
    import matplotlib  # noqa: F401
    import numpy as np
    import pandas  # noqa: F401
except ImportError as e:
    print(f"analysis_test: skipped: {e} (Debian: python3-matplotlib python3-numpy "
          "python3-pandas)")
    sys.exit(SKIP)

import array_heatmap  # noqa: E402
import chain_profile  # noqa: E402
import common  # noqa: E402
import figures  # noqa: E402
import latency_breakdown  # noqa: E402
import latency_histogram  # noqa: E402
import pareto_plot  # noqa: E402,F401
import pxpl5_rows_squares  # noqa: E402
import array_scaling  # noqa: E402
import pxpl5_workload  # noqa: E402
import sensitivity_map  # noqa: E402
import sweep_plot  # noqa: E402
import utilisation_timeline  # noqa: E402
import wang_accuracy  # noqa: E402
import wang_arithmetic  # noqa: E402
import wang_substages  # noqa: E402
import pixelflow_passes  # noqa: E402
import hidden_line_polygons  # noqa: E402
import sort_first_frames  # noqa: E402
import sort_first_migration  # noqa: E402

PYTHON = sys.executable


def run_script(name, *args):
    return subprocess.run([PYTHON, os.path.join(ANALYSIS, name), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def png_size(path):
    """(width, height) from the PNG header; fails the test if it is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


class PngMixin:
    def assertGoodPng(self, path, min_w=300, min_h=200):
        self.assertTrue(os.path.exists(path), path)
        w, h = png_size(path)
        self.assertGreaterEqual(w, min_w)
        self.assertGreaterEqual(h, min_h)
        self.assertGreater(os.path.getsize(path), 5000)  # more than an empty canvas
        import matplotlib.image as mpimg

        pixels = mpimg.imread(path)
        self.assertGreater(float(pixels[..., :3].std()), 0.02, "the picture is blank")
        # No half-written temporary left beside it.
        folder = os.path.dirname(os.path.abspath(path))
        self.assertEqual([f for f in os.listdir(folder) if f.endswith(".partial")], [])


class ScratchTest(unittest.TestCase, PngMixin):
    """A test with its own scratch folder, self.dir, removed afterwards."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="rtsim-analysis-")

    def tearDown(self):
        shutil.rmtree(self.dir)


class SweepPlotTest(ScratchTest):
    def setUp(self):
        super().setUp()
        self.csv = os.path.join(self.dir, "results.csv")
        with open(self.csv, "w") as f:
            f.write("machine,scene,pert_count,link.bit_time,simulated_time_s,wall_time_s,"
                    "rays.total,modules.host.utilization,exit_status,error,unrelated\n"
                    "machine-b,builtin:npp-404,1,200 ns,8.0,1.5,100,0.9,0,,a\n"
                    "machine-b,builtin:npp-404,2,200 ns,4.0,1.2,100,0.8,0,,b\n"
                    "machine-b,builtin:npp-404,4,200 ns,2.5,1.1,100,0.7,0,,c\n"
                    "machine-b,builtin:npp-404,4,200 ns,1.5,1.1,100,0.7,0,,repeat\n"
                    "machine-b,builtin:npp-408,1,400 ns,10.0,2.0,100,0.9,0,,d\n"
                    "machine-b,builtin:npp-408,2,400 ns,6.0,2.0,100,0.8,0,,e\n"
                    "machine-b,builtin:npp-408,8,400 ns,,0,0,0,1,crashed,f\n")

    def test_speed_up_per_scene_against_the_one_pert_row(self):
        df = sweep_plot.read_results(self.csv)
        series, cats = sweep_plot.compute_series(df, "pert_count", "simulated_time_s", "scene",
                                                 "pert_count=1")
        self.assertIsNone(cats)
        xs, ys = series["builtin:npp-404"]
        np.testing.assert_allclose(xs, [1, 2, 4])
        # 8/8, 8/4, 8/mean(2.5, 1.5): repeated points are averaged before the ratio is drawn.
        np.testing.assert_allclose(ys, [1.0, 2.0, 4.0])
        xs, ys = series["builtin:npp-408"]
        np.testing.assert_allclose(xs, [1, 2])  # the failed 8-PERT point is left out
        np.testing.assert_allclose(ys, [1.0, 10.0 / 6.0])

    def test_one_line_per_combination_of_several_group_columns(self):
        df = sweep_plot.read_results(self.csv)
        series, _ = sweep_plot.compute_series(df, "pert_count", "simulated_time_s",
                                              "scene,link.bit_time", "pert_count=1")
        self.assertEqual(sorted(series), ["builtin:npp-404, 200 ns", "builtin:npp-408, 400 ns"])
        np.testing.assert_allclose(series["builtin:npp-404, 200 ns"][1], [1.0, 2.0, 4.0])

    def test_units_spelling_and_plain_values(self):
        df = sweep_plot.read_results(self.csv)
        # "200 ns" reads as 2e-7 s; utilisation finds the utilization column.
        series, _ = sweep_plot.compute_series(df, "link.bit_time", "modules.host.utilisation",
                                              "scene")
        xs, ys = series["builtin:npp-404"]
        np.testing.assert_allclose(xs, [2e-7])
        np.testing.assert_allclose(ys, [(0.9 + 0.8 + 0.7 + 0.7) / 4])
        self.assertAlmostEqual(common.to_number("5 MHz"), 5e6)
        self.assertAlmostEqual(common.to_number("1.5 Gbit/s"), 1.5e9)
        self.assertIsNone(common.to_number("scanline"))

    def test_a_class_band_is_shaded_around_its_mean(self):
        path = os.path.join(self.dir, "classes.csv")
        with open(path, "w") as f:
            f.write("array.rows,status,modules.host.utilization,"
                    "module_classes.node*.utilization.min,module_classes.node*.utilization.mean,"
                    "module_classes.node*.utilization.max\n"
                    "2,ok,0.2,0.1,0.5,0.9\n4,ok,0.3,0.05,0.4,0.95\n")
        df = sweep_plot.read_results(path)
        ys = ["module_classes.node*.utilization.mean", "modules.host.utilization"]
        bands = sweep_plot.parse_bands(
            ["module_classes.node*.utilization.mean=module_classes.node*.utilization.min,"
             "module_classes.node*.utilization.max"], ys)
        series, _ = sweep_plot.compute_multi(df, "array.rows", ys, None)
        self.assertEqual(sorted(series), ["host", "node* (mean)"])
        band = sweep_plot.compute_bands(df, "array.rows", ys, bands)
        self.assertEqual(list(band), ["node* (mean)"])
        xs, lo, hi = band["node* (mean)"]
        np.testing.assert_allclose(xs, [2, 4])
        np.testing.assert_allclose(lo, [0.1, 0.05])
        np.testing.assert_allclose(hi, [0.9, 0.95])
        out = os.path.join(self.dir, "band.png")
        self.assertEqual(sweep_plot.main([path, out, "--x", "array.rows", "--y", ys[0], "--y", ys[1],
                                          "--band", f"{ys[0]}=module_classes.node*.utilization.min,"
                                          "module_classes.node*.utilization.max"]), 0)
        self.assertTrue(os.path.getsize(out) > 0)
        with self.assertRaises(common.InputProblem):
            sweep_plot.parse_bands(["modules.host.utilization=a"], ys)
        with self.assertRaises(common.InputProblem):
            sweep_plot.parse_bands(["nope=a,b"], ys)

    def test_jsonl_nested_objects_become_dotted_columns(self):
        path = os.path.join(self.dir, "results.jsonl")
        with open(path, "w") as f:
            for n, t in ((1, 9.0), (3, 3.0)):
                f.write(json.dumps({"machine": "m", "scene": "s", "peripheral.grid.divisions": n,
                                    "simulated_time_s": t, "rays": {"total": 7},
                                    "status": "ok"}) + "\n")
            f.write(json.dumps({"machine": "m", "scene": "s", "peripheral.grid.divisions": 5,
                                "status": "failed", "error": "boom"}) + "\n")
        df = sweep_plot.read_results(self.dir)  # the folder: results.jsonl is found
        series, _ = sweep_plot.compute_series(df, "peripheral.grid.divisions", "rays.total")
        np.testing.assert_allclose(series["all"][0], [1, 3])
        np.testing.assert_allclose(series["all"][1], [7, 7])
        series, _ = sweep_plot.compute_series(df, "peripheral.grid.divisions",
                                              "simulated_time_s", None, "simulated_time_s",
                                              "fraction")
        np.testing.assert_allclose(series["all"][1], [1.0, 1.0])

    def test_several_y_columns_one_line_each(self):
        path = os.path.join(self.dir, "results.jsonl")
        with open(path, "w") as f:
            for scene in ("a", "b"):
                for n, busy in ((1, 0.9), (2, 0.6)):
                    f.write(json.dumps({"scene": scene, "pert_count": n, "status": "ok",
                                        "modules.host.utilization": busy,
                                        "modules.bus.prim.utilization": busy / 3}) + "\n")
        df = sweep_plot.read_results(path)
        ys = ["modules.host.utilization", "modules.bus.prim.utilization"]
        self.assertEqual(sweep_plot.short_names(ys), (["host", "bus.prim"],
                                                       "modules.*.utilization"))
        self.assertEqual(sweep_plot.short_names(["simulated_time_s", "rays.total"]),
                         (["simulated_time_s", "rays.total"], None))
        series, cats = sweep_plot.compute_multi(df, "pert_count", ys, "scene")
        self.assertIsNone(cats)
        self.assertEqual(sorted(series), ["a: bus.prim", "a: host", "b: bus.prim", "b: host"])
        np.testing.assert_allclose(series["b: bus.prim"][1], [0.3, 0.2])
        series, _ = sweep_plot.compute_multi(df, "scene", ys, None)  # categories on x
        self.assertEqual(sorted(series), ["bus.prim", "host"])
        np.testing.assert_allclose(series["host"][0], [0, 1])
        out = os.path.join(self.dir, "busy.png")
        r = run_script("sweep_plot.py", path, out, "--x", "pert_count", "--y", ys[0], "--y",
                       ys[1])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_command_line_writes_a_png_and_rejects_an_unknown_column(self):
        out = os.path.join(self.dir, "speedup.png")
        r = run_script("sweep_plot.py", self.csv, out, "--x", "pert_count", "--y",
                       "simulated_time_s", "--ratio-to", "pert_count=1", "--logx")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        r = run_script("sweep_plot.py", self.csv, out + "2", "--x", "pert_count", "--y",
                       "simulated_tme_s")
        self.assertEqual(r.returncode, 2)
        self.assertIn("did you mean simulated_time_s", r.stderr)
        self.assertFalse(os.path.exists(out + "2"))
        self.assertEqual(run_script("sweep_plot.py", "--help").returncode, 0)


def make_trace():
    """Two tracks and a queue counter over [0, 40) us."""
    meta = [
        {"name": "thread_name", "ph": "M", "pid": 1, "tid": 2, "args": {"name": "bus"}},
        {"name": "thread_name", "ph": "M", "pid": 1, "tid": 3, "args": {"name": "cpu"}},
    ]
    ev = [
        # bus: [0, 10) and [20, 30) us -> windows of 10 us: 1, 0, 1, 0
        {"name": "x", "ph": "X", "ts": 0.0, "dur": 10.0, "pid": 1, "tid": 2},
        {"name": "x", "ph": "X", "ts": 20.0, "dur": 10.0, "pid": 1, "tid": 2},
        # cpu: [5, 15) and an overlapping [10, 15) (counted once), [35, 40)
        {"name": "y", "ph": "X", "ts": 5.0, "dur": 10.0, "pid": 1, "tid": 3},
        {"name": "y", "ph": "X", "ts": 10.0, "dur": 5.0, "pid": 1, "tid": 3},
        {"name": "y", "ph": "X", "ts": 35.0, "dur": 5.0, "pid": 1, "tid": 3},
        # queue depth: 2 over [0, 20), 4 over [20, 40)
        {"name": "q.depth", "ph": "C", "ts": 0.0, "pid": 1, "tid": 2, "args": {"value": 2}},
        {"name": "q.depth", "ph": "C", "ts": 20.0, "pid": 1, "tid": 2, "args": {"value": 4}},
        {"name": "q.depth", "ph": "C", "ts": 40.0, "pid": 1, "tid": 2, "args": {"value": 0}},
    ]
    return {"traceEvents": meta + ev[::-1], "displayTimeUnit": "ns"}  # out of time order


class UtilisationTimelineTest(ScratchTest):
    def test_busy_fraction_per_window_from_a_trace(self):
        edges, busy, depth = utilisation_timeline.busy_from_trace(make_trace(), windows=4)
        np.testing.assert_allclose(edges, [0, 10e-6, 20e-6, 30e-6, 40e-6], atol=1e-15)
        np.testing.assert_allclose(busy["bus"], [1.0, 0.0, 1.0, 0.0], atol=1e-9)
        np.testing.assert_allclose(busy["cpu"], [0.5, 0.5, 0.0, 0.5], atol=1e-9)
        np.testing.assert_allclose(depth["q.depth"], [2.0, 2.0, 4.0, 4.0], atol=1e-9)
        # Windows given by width; a regular expression keeps only some tracks.
        edges, busy, _ = utilisation_timeline.busy_from_trace(make_trace(), window_s=20e-6,
                                                              modules="^bus$")
        self.assertEqual(list(busy), ["bus"])
        np.testing.assert_allclose(busy["bus"], [0.5, 0.5], atol=1e-9)

    def test_busy_counters_are_the_busy_time_and_the_window_the_range(self):
        # rtsim's traces: a module's busy level as a counter NAME.busy (its slices are only its
        # transactions) and the range the trace covers in otherData.
        trace = make_trace()
        trace["traceEvents"] += [
            {"name": "bus.busy", "ph": "C", "ts": 0.0, "pid": 1, "tid": 2, "args": {"value": 1}},
            {"name": "bus.busy", "ph": "C", "ts": 30.0, "pid": 1, "tid": 2, "args": {"value": 0}},
            {"name": "bus.busy", "ph": "C", "ts": 80.0, "pid": 1, "tid": 2, "args": {"value": 0}},
        ]
        trace["otherData"] = {"rtsim_window_s": [10e-6, 90e-6]}  # --trace-window
        edges, busy, depth = utilisation_timeline.busy_from_trace(trace, windows=4)
        np.testing.assert_allclose(edges, [10e-6, 30e-6, 50e-6, 70e-6, 90e-6], atol=1e-15)
        np.testing.assert_allclose(busy["bus"], [1.0, 0.0, 0.0, 0.0], atol=1e-9)
        np.testing.assert_allclose(busy["cpu"], [0.25, 0.25, 0.0, 0.0], atol=1e-9)  # slices
        self.assertNotIn("bus.busy", depth)
        np.testing.assert_allclose(depth["q.depth"], [3.0, 2.0, 0.0, 0.0], atol=1e-9)
        # A trace of the whole run (from 0) is drawn over the frame.
        trace["otherData"] = {"rtsim_window_s": [0.0, 90e-6],
                              "rtsim_stats_interval_s": [0.0, 80e-6]}
        edges, busy, depth = utilisation_timeline.busy_from_trace(trace, windows=4)
        np.testing.assert_allclose(edges, [0, 20e-6, 40e-6, 60e-6, 80e-6], atol=1e-15)
        np.testing.assert_allclose(busy["bus"], [1.0, 0.5, 0.0, 0.0], atol=1e-9)
        np.testing.assert_allclose(depth["q.depth"], [2.0, 4.0, 0.0, 0.0], atol=1e-9)

    def test_windows_from_stats_json(self):
        stats = {"machine": "m", "scene": "s", "modules": {
            "host": {"busy_s": 1.0, "utilization_windows": {
                "begin_s": 2.0, "window_s": 0.5, "values": [1.0, 0.5, 0.0]}},
            "queue": {"busy_s": 0.0}}}
        edges, series = utilisation_timeline.busy_from_stats(stats)
        np.testing.assert_allclose(edges, [2.0, 2.5, 3.0, 3.5])
        self.assertEqual(list(series), ["host"])
        np.testing.assert_allclose(series["host"][1], [1.0, 0.5, 0.0])

    def test_command_line_on_a_trace_and_on_stats(self):
        trace = os.path.join(self.dir, "trace.json")
        with open(trace, "w") as f:
            json.dump(make_trace(), f)
        out = os.path.join(self.dir, "t.png")
        r = run_script("utilisation_timeline.py", trace, out, "--windows", "8")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        stats = os.path.join(self.dir, "stats.json")
        with open(stats, "w") as f:
            json.dump({"modules": {"host": {"utilization_windows": {
                "begin_s": 0.0, "window_s": 1e-3, "values": [0.2, 0.9, 0.4]}}}}, f)
        out2 = os.path.join(self.dir, "s.png")
        r = run_script("utilisation_timeline.py", stats, out2)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out2)
        with open(stats, "w") as f:
            json.dump({"modules": {"host": {"busy_s": 1}}}, f)
        r = run_script("utilisation_timeline.py", stats, out2)
        self.assertEqual(r.returncode, 2)
        self.assertIn("utilization_windows", r.stderr)


class LatencyHistogramTest(ScratchTest):
    def test_series_and_png(self):
        stats = {"machine": "m", "scene": "s", "ray_latency_s": {
            "count": 7, "mean": 2.5e-6, "p50": 2e-6, "p99": 4e-6, "max": 4e-6,
            "histogram": {"edges_s": [1e-6, 2e-6, 4e-6, 8e-6], "counts": [1, 4, 2]}}}
        edges, counts, marks = latency_histogram.histogram_series(stats)
        self.assertEqual(edges, [1e-6, 2e-6, 4e-6, 8e-6])
        self.assertEqual(counts, [1, 4, 2])
        self.assertEqual(marks, {"mean": 2.5e-6, "p50": 2e-6, "p99": 4e-6, "max": 4e-6})
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump(stats, f)
        out = os.path.join(self.dir, "l.png")
        r = run_script("latency_histogram.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        with self.assertRaises(Exception):
            latency_histogram.histogram_series({"ray_latency_s": {
                "histogram": {"edges_s": [1, 2], "counts": [1, 2]}}})
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            f.write("{ not json")
        r = run_script("latency_histogram.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("stats.json:1", r.stderr)


class ArrayHeatmapTest(ScratchTest):
    def stats(self):
        return {"machine": "machine-c", "scene": "s",
                "array": {"mapping": "straight", "depth_axis": "z", "subvolumes": 2,
                          "node_busy_fraction": [[0.5, 0.25], [0.125, 0.0]]},
                "modules": {"node0.link_e": {"utilization": 0.2},
                            "node3.link_n": {"utilization": 0.1},
                            "node0": {"utilization": 0.5},
                            "node1": {"utilization": 0.25},
                            "node1.pipeline": {"utilization": 0.875},
                            "node2.memory": {"utilization": 0.0625}}}

    def test_series_and_png(self):
        busy, limit, links, desc = array_heatmap.array_series(self.stats())
        # Each processor's busiest resource: node1's pipeline, not its CPU; node2's CPU.
        self.assertEqual(busy, [[0.5, 0.875], [0.125, 0.0]])
        self.assertEqual(limit, [["C", "P"], ["C", "C"]])
        self.assertEqual(sorted(links), [(0, 0, "e", 0.2), (1, 1, "n", 0.1)])
        self.assertIn("straight", desc)
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump(self.stats(), f)
        out = os.path.join(self.dir, "a.png")
        r = run_script("array_heatmap.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        bad = self.stats()
        bad["array"]["node_busy_fraction"] = [[0.5, 0.25], [0.1]]
        with self.assertRaises(Exception):
            array_heatmap.array_series(bad)
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"machine": "machine-a"}, f)
        r = run_script("array_heatmap.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("node_busy_fraction", r.stderr)


class SensitivityMapTest(ScratchTest):
    def doc(self):
        e = lambda f, p, label, change, flips: {"figure": f, "param": p, "label": label,
                                                "relative_change": change, "flips": flips}
        return {"mode": "quick", "entries": [
            e("V19", "node.clock", "x0.5", -0.26, False), e("V19", "node.clock", "x2", 0.2, True),
            e("X4b", "master.assign_time", "x0.5", -0.11, True),
            e("X4b", "gp.clock", "x2", None, False)]}

    def test_cells_and_png(self):
        figures, params, cells = sensitivity_map.cells(self.doc())
        self.assertEqual(figures, ["V19", "X4b"])
        self.assertEqual(params, ["node.clock", "master.assign_time", "gp.clock"])
        # The largest move, and framed if any move turns the verdict.
        self.assertEqual(cells[("V19", "node.clock")], (-0.26, True))
        self.assertTrue(np.isnan(cells[("X4b", "gp.clock")][0]))
        path = os.path.join(self.dir, "validation-sensitivity.json")
        with open(path, "w") as f:
            json.dump(self.doc(), f)
        out = os.path.join(self.dir, "s.png")
        r = run_script("sensitivity_map.py", path, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        path = os.path.join(self.dir, "x.json")
        with open(path, "w") as f:
            json.dump({"rows": []}, f)
        r = run_script("sensitivity_map.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("entries", r.stderr)


class ChainProfileTest(ScratchTest):
    def stats(self):
        return {"machine": "machine-d", "scene": "s", "pipeline": {
            "engines": 6, "polygons": 4, "along_chain": {
                "engines": 6, "busy_fraction": 0.25, "first_engine": [0, 2, 4],
                "overwrites_per_description": [0.5, 0.125, 0.0],
                "answers_per_description": [0.25, 0.125, 0.0]}}}

    def test_series_and_png(self):
        first, busy, over, ans, engines, polygons = chain_profile.chain_series(self.stats())
        self.assertEqual(first, [0, 2, 4])
        self.assertEqual(busy, 0.25)
        self.assertEqual(over, [0.5, 0.125, 0.0])
        self.assertEqual(ans, [0.25, 0.125, 0.0])
        self.assertEqual((engines, polygons), (6, 4))
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump(self.stats(), f)
        out = os.path.join(self.dir, "c.png")
        r = run_script("chain_profile.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_busy_over_time_of_watched_processors(self):
        stats = self.stats()
        stats["pipeline"]["along_chain"]["busy_windows"] = {
            "engines": [0, 3, 5], "begin_s": 0.001, "window_s": 0.0005,
            "busy": [[1, 0.5, 0, 0], [0, 1, 0.5, 0], [0, 0, 1, 0.25]]}
        engines, begin, width, rows = chain_profile.busy_windows(stats)
        self.assertEqual(engines, [0, 3, 5])
        self.assertEqual(rows[2], [0, 0, 1, 0.25])
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump(stats, f)
        out = os.path.join(self.dir, "c.png")
        r = run_script("chain_profile.py", path, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        stats["pipeline"]["along_chain"]["busy_windows"]["busy"] = [[1], [0, 1], [0]]
        with self.assertRaises(Exception):
            chain_profile.busy_windows(stats)

    def test_bad_input(self):
        bad = self.stats()
        bad["pipeline"]["along_chain"]["answers_per_description"] = [0.1]
        with self.assertRaises(Exception):
            chain_profile.chain_series(bad)
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"machine": "machine-a"}, f)
        r = run_script("chain_profile.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("along_chain", r.stderr)


class WangSubstagesTest(ScratchTest):
    def stats(self):
        return {"machine": "machine-e", "scene": "s", "simulated_time_s": 1e-3,
                "modules": {"host": {"utilization": 0.75}},
                "wang": {"loop_stages": 2, "cycle_s": 2e-6, "jobs": 250, "dsps": 9,
                         "stage0": {"split_u": {"dsps": 1, "cycles": 10, "time_s": 1e-6}},
                         "substages": {
                             "split_u": {"dsps": 4, "units": 4, "cycles": 20, "time_s": 2e-6},
                             "culler": {"dsps": 0, "units": 0, "cycles": 0, "time_s": 8e-7}}}}

    def test_rows_busy_and_png(self):
        rows, cycle, jobs, frame, host = wang_substages.substage_rows(self.stats())
        self.assertEqual([r[0] for r in rows], ["stage0.split_u", "loop.split_u", "loop.culler"])
        self.assertEqual(rows[1], ("loop.split_u", 4, 20, 2e-6))
        self.assertEqual((cycle, jobs, frame, host), (2e-6, 250, 1e-3, 0.75))
        # 250 jobs of 2 us in 1 ms: busy half the frame; 0.8 us: a fifth.
        busy = wang_substages.busy_fractions(rows, jobs, frame)
        self.assertAlmostEqual(busy[1], 0.5)
        self.assertAlmostEqual(busy[2], 0.2)
        with open(os.path.join(self.dir, "stats.json"), "w") as f:
            json.dump(self.stats(), f)
        out = os.path.join(self.dir, "w.png")
        r = run_script("wang_substages.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"machine": "machine-a"}, f)
        r = run_script("wang_substages.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("wang.substages", r.stderr)


class PixelflowPassesTest(ScratchTest):
    def stats(self):
        return {"machine": "pixelflow", "scene": "s", "spp": 5, "simulated_time_s": 0.025,
                "params": {"composition.link.lanes": "256",
                           "composition.link.bit_rate": "204.8 Mbit/s"},
                "pixelflow": {"rasterizers": 3, "shaders": 12, "passes": {
                    "shadow0": {"begin_s": 0.0, "done_s": 0.0061, "rasterize_busiest_s": 1e-4,
                                "shade_busiest_s": 0.0, "network_bytes": 1048576},
                    "camera": {"begin_s": 0.012, "done_s": 0.025, "rasterize_busiest_s": 0.0096,
                               "shade_busiest_s": 0.0086, "network_bytes": 60620800}}}}

    def test_rows_rate_and_png(self):
        rows, frame = pixelflow_passes.pass_rows(self.stats())
        self.assertEqual([r[0] for r in rows], ["shadow0", "camera"])
        self.assertEqual(rows[1][1:3], (0.012, 0.025))
        self.assertEqual(frame, 0.025)
        # 256 lanes of 204.8 Mbit/s: 6.5536 GB/s (seed 004 L120's 8K depths in 5 us).
        self.assertAlmostEqual(pixelflow_passes.network_rate(self.stats()), 6.5536e9)
        with open(os.path.join(self.dir, "stats.json"), "w") as f:
            json.dump(self.stats(), f)
        out = os.path.join(self.dir, "p.png")
        r = run_script("pixelflow_passes.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"machine": "pixelflow", "pixelflow": {"passes": {}}}, f)
        r = run_script("pixelflow_passes.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("pixelflow.passes", r.stderr)


class WangAccuracyTest(ScratchTest):
    def row(self, n, missed, phantom, another):
        a = "wang.accuracy.rays."
        return {"point": n, "status": "ok", "bezier.iterations": n, a + "compared": 1000,
                a + "both": 400 - missed, a + "missed": missed, a + "phantom": phantom,
                a + "another_surface": another, a + "point_error.p50": 2.0 ** -(n + 2),
                a + "point_error.p90": 2.0 ** -(n + 1), a + "point_error.p99": 2.0 ** -n,
                a + "pixel_error.p50": 2.0 ** (4 - n), a + "pixel_error.p90": 2.0 ** (5 - n),
                a + "pixel_error.p99": 2.0 ** (6 - n), "wang.latency_s": n * 5e-6,
                "wang.dsps": 60 * n + 4, "wang.throughput_rpi_per_s": 9.16e5}

    def write(self, rows):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for r in rows:
                f.write(json.dumps(r) + "\n")

    def test_table_fewest_wrong_and_png(self):
        # 400 reference hits each; wrong answers 40, 8, 12 at 4, 6, 8 stages.
        self.write([self.row(8, 10, 0, 2), self.row(4, 0, 36, 4), self.row(6, 2, 4, 2)])
        rows = wang_accuracy.accuracy_table(sweep_plot.read_results(self.dir))
        self.assertEqual([r["stages"] for r in rows], [4, 6, 8])
        self.assertAlmostEqual(rows[0]["disagreement"], 36 / 400)
        self.assertAlmostEqual(rows[0]["wrong"], 40 / 400)
        self.assertAlmostEqual(rows[2]["wrong"], 12 / 400)
        self.assertEqual(rows[1]["width"], 2.0 ** -7)
        self.assertEqual(wang_accuracy.fewest_wrong(rows), 6)
        self.assertIn("| 6 | 364 |", wang_accuracy.markdown(rows))
        out = os.path.join(self.dir, "a.png")
        r = run_script("wang_accuracy.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("fewest wrong answers at 6 stages", r.stdout)
        self.assertGoodPng(out)

    def test_a_sweep_without_the_check(self):
        row = self.row(4, 0, 0, 0)
        del row["wang.accuracy.rays.missed"]
        self.write([row])
        r = run_script("wang_accuracy.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("wang.accuracy.rays.missed", r.stderr)


class WangArithmeticTest(ScratchTest):
    def row(self, kind, bits, missed, phantom, another, p50):
        a = "wang.accuracy.rays."
        return {"point": bits, "status": "ok", "bezier.arithmetic": kind,
                "bezier.fixed_bits": bits, a + "both": 400 - missed, a + "missed": missed,
                a + "phantom": phantom, a + "another_surface": another,
                a + "point_error.p50": p50, a + "point_error.p99": 4 * p50,
                a + "pixel_error.p99": 0.1}

    def write(self, rows):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for r in rows:
                f.write(json.dumps(r) + "\n")

    def test_table_and_png(self):
        # 400 reference hits each; the narrow word loses 200, the wide ones 8 like float32.
        self.write([self.row("fixed", 24, 4, 0, 4, 1e-4), self.row("float32", 24, 4, 0, 4, 1e-4),
                    self.row("fixed", 12, 100, 60, 40, 3e-3)])
        table = wang_arithmetic.arithmetic_table(sweep_plot.read_results(self.dir))
        self.assertEqual(list(table), ["the sweep"])
        floats, fixed = table["the sweep"]
        self.assertEqual(list(floats), ["float32"])
        self.assertEqual([r["bits"] for r in fixed], [12, 24])
        self.assertAlmostEqual(fixed[0]["wrong"], 200 / 400)
        self.assertAlmostEqual(floats["float32"]["wrong"], 8 / 400)
        self.assertIn("| the sweep | fixed 12 bits | 100 | 60 | 40 | 50.00% |",
                      wang_arithmetic.markdown(table))
        out = os.path.join(self.dir, "a.png")
        r = run_script("wang_arithmetic.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_a_series_per_scene_and_view(self):
        rows = []
        for scene in ("builtin:a", "builtin:b"):
            for azimuth in (0, 120):
                for kind, bits in (("float32", 24), ("fixed", 16), ("fixed", 24)):
                    row = self.row(kind, bits, 4, 0, 4, 1e-4)
                    row.update({"scene": scene, "view.azimuth_deg": azimuth})
                    rows.append(row)
        self.write(rows)
        table = wang_arithmetic.arithmetic_table(sweep_plot.read_results(self.dir))
        self.assertEqual(sorted(table), ["builtin:a, azimuth 0", "builtin:a, azimuth 120",
                                         "builtin:b, azimuth 0", "builtin:b, azimuth 120"])
        self.assertEqual([r["bits"] for r in table["builtin:b, azimuth 120"][1]], [16, 24])
        out = os.path.join(self.dir, "s.png")
        r = run_script("wang_arithmetic.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_a_sweep_without_fixed_point_or_the_check(self):
        self.write([self.row("float32", 24, 4, 0, 4, 1e-4)])
        r = run_script("wang_arithmetic.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("no fixed-point point", r.stderr)
        row = self.row("fixed", 16, 0, 0, 0, 1e-4)
        del row["wang.accuracy.rays.missed"]
        self.write([row])
        r = run_script("wang_arithmetic.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("wang.accuracy.rays.missed", r.stderr)


class Pxpl5RowsSquaresTest(ScratchTest):
    def write(self, points):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for scheme, dist, rate, cover in points:
                f.write(json.dumps({"status": "ok", "assign.scheme": scheme,
                                    "camera.distance": dist,
                                    "pxpl5.last_frame_per_second": rate,
                                    "pxpl5.screen_coverage": cover}) + "\n")

    def test_table_crossing_and_png(self):
        # Squares faster near (full screen), rows faster far away.
        self.write([("rows", 0.5, 5.0, 0.9), ("squares", 0.5, 10.0, 0.95),
                    ("rows", 2.0, 40.0, 0.1), ("squares", 2.0, 20.0, 0.4),
                    ("rows", 1.0, 12.0, 0.5), ("squares", 1.0, 15.0, 0.7)])
        rows = pxpl5_rows_squares.table(sweep_plot.read_results(self.dir))
        self.assertEqual(list(rows), [0.5, 1.0, 2.0])
        self.assertEqual(rows[2.0]["coverage"], 0.1)  # the rows' coverage, not the squares'
        self.assertEqual(pxpl5_rows_squares.crossing(rows), (0.5, 0.1))
        out = os.path.join(self.dir, "f.png")
        r = run_script("pxpl5_rows_squares.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 2 | 10.0% | 40.00 | 20.00 | 0.50 |", r.stdout)
        self.assertIn("squares win down to 50.0% coverage, rows from 10.0%", r.stdout)
        self.assertGoodPng(out)

    def test_bad_input(self):
        self.write([("rows", 0.5, 5.0, 0.9)])
        r = run_script("pxpl5_rows_squares.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("rows and squares", r.stderr)


class ArrayScalingTest(ScratchTest):
    def write(self, points):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for scene, side, sub, frame in points:
                f.write(json.dumps({"status": "ok", "scene": scene, "array.rows": side,
                                    "array.cols": side, "array.subvolumes": sub,
                                    "simulated_time_s": frame,
                                    "module_classes": {"node*": {"utilization": {
                                        "mean": 0.5, "max": 0.75}}}}) + "\n")

    def test_lines_table_and_png(self):
        self.write([("s", 4, 0, 1.0), ("s", 2, 0, 8.0), ("s", 2, 4, 4.0), ("s", 4, 4, 1.0)])
        data = array_scaling.lines(sweep_plot.read_results(self.dir))
        self.assertEqual(data[("s", "grows")], [(4, 8.0, 0.5, 0.75), (16, 1.0, 0.5, 0.75)])
        self.assertEqual(data[("s", "4")][1][1], 1.0)
        out = os.path.join(self.dir, "f.png")
        r = run_script("array_scaling.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| s | grows | 8000 ms, 1x, 50/75% | 1000 ms, 8x, 50/75% |", r.stdout)
        self.assertGoodPng(out)

    def test_bad_input(self):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            f.write(json.dumps({"status": "ok", "scene": "s", "simulated_time_s": 1.0}) + "\n")
        r = run_script("array_scaling.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("array.rows", r.stderr)


class SortFirstMigrationTest(ScratchTest):
    def write(self, points):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for i, (side, spin, frames) in enumerate(points):
                d = f"points/{i:04d}"
                os.makedirs(os.path.join(self.dir, d))
                stats = {"sort_first": {
                    "per_frame": [{"migrated_percent": p} for p in frames],
                    "migrated_percent": {"mean": sum(frames[1:]) / (len(frames) - 1),
                                         "p95": max(frames[1:])}}}
                with open(os.path.join(self.dir, d, "stats.json"), "w") as s:
                    json.dump(stats, s)
                f.write(json.dumps({"status": "ok", "dir": d, "regions": side,
                                    "camera.spin": spin}) + "\n")

    def test_series_table_and_png(self):
        self.write([(4, 4.5, [120.0, 4.0, 5.0]), (8, 4.5, [130.0, 8.0, 9.0]),
                    (4, 9, [120.0, 8.0, 9.0])])
        data = sort_first_migration.points(self.dir)
        # The first frame (the random distribution's) is left out.
        self.assertEqual(data[4.5][4], ([4.0, 5.0], 4.5, 5.0))
        out = os.path.join(self.dir, "f.png")
        r = run_script("sort_first_migration.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 4.5 | 4.50 (5.00) | 8.50 (9.00) |", r.stdout)
        self.assertIn("| 9 | 8.50 (9.00) | - |", r.stdout)
        self.assertGoodPng(out)

    def test_bad_input(self):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            f.write(json.dumps({"status": "ok", "dir": "points/0000", "regions": 4,
                                "camera.spin": 4.5}) + "\n")
        os.makedirs(os.path.join(self.dir, "points", "0000"))
        with open(os.path.join(self.dir, "points", "0000", "stats.json"), "w") as s:
            s.write("{}")
        r = run_script("sort_first_migration.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("sort_first.per_frame", r.stderr)


class HiddenLinePolygonsTest(ScratchTest):
    def write(self, points):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            for i, (polygons, frame, first, mean) in enumerate(points):
                d = f"points/{i:04d}"
                os.makedirs(os.path.join(self.dir, d))
                stats = {"hidden_line": {
                    "polygons": polygons, "plane_processors": 5 * polygons,
                    "frame_time_s": frame,
                    "segment_latency_s": {"first": first, "mean": mean, "max": mean},
                    "along_pipe": [{"link_utilization": 0.2}, {"link_utilization": 0.25}]}}
                with open(os.path.join(self.dir, d, "stats.json"), "w") as s:
                    json.dump(stats, s)
                f.write(json.dumps({"status": "ok", "dir": d,
                                    "scene": f"builtin:ullner-random-{polygons}"}) + "\n")

    def test_table_and_png(self):
        self.write([(200, 0.05, 0.02, 0.03), (100, 0.02, 0.01, 0.012)])
        data = hidden_line_polygons.points(self.dir)
        self.assertEqual([p[0] for p in data], [100, 200])  # by polygons
        out = os.path.join(self.dir, "h.png")
        r = run_script("hidden_line_polygons.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 100 | 500 | 20.0 | 10.0 | 12.0 | 4.0 |", r.stdout)
        self.assertGoodPng(out)

    def test_bad_input(self):
        with open(os.path.join(self.dir, "results.jsonl"), "w") as f:
            f.write(json.dumps({"status": "ok", "dir": "points/0000",
                                "scene": "builtin:ullner-random-100"}) + "\n")
        os.makedirs(os.path.join(self.dir, "points", "0000"))
        with open(os.path.join(self.dir, "points", "0000", "stats.json"), "w") as s:
            s.write("{}")
        r = run_script("hidden_line_polygons.py", self.dir, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("hidden_line.segment_latency_s", r.stderr)


class SortFirstFramesTest(ScratchTest):
    def test_rows_and_png(self):
        frames = [{"frame": f, "migrated_percent": p, "time_s": 0.002, "load_imbalance": 2.0,
                   "bytes": {"view": 64, "redistribution": b, "pixels": 300, "partial": 0}}
                  for f, p, b in ((0, 120.0, 5000), (1, 4.0, 200), (2, 5.0, 250))]
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"scene": "builtin:plb-head", "sort_first": {
                "sort": "first", "region_grid": "4x4", "interconnect": "ring",
                "per_frame": frames, "migrated_percent": {"mean": 4.5, "p95": 5.0}}}, f)
        _, stats = common.read_stats(path)
        rows = sort_first_frames.frame_rows(stats)
        self.assertEqual(rows[1][:2], (1, 4.0))
        self.assertEqual(rows[2][2]["redistribution"], 250.0)
        out = os.path.join(self.dir, "f.png")
        r = run_script("sort_first_frames.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        with open(path, "w") as f:
            json.dump({"sort_first": {}}, f)
        r = run_script("sort_first_frames.py", path, out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("sort_first.per_frame", r.stderr)


class ParetoPlotTest(ScratchTest):
    def test_png_and_bad_input(self):
        rows = [{"machine": m, "scene": sc, "setting": st, "frame_s": 1.0, "wall_s": w,
                 "speedup": 1.0 / w, "error": e, **extra}
                for m in ("machine-a", "machine-b")
                for sc in ("builtin:a", "builtin:b")
                for st, w, e, extra in (("reference", 1.0, 0.0, {}),
                                        ("quantum 1 ms", 0.8, 0.0, {}),
                                        ("sample 4", 0.1, 0.005, {"ci_holds": True}),
                                        ("sample 16", 0.05, 0.2, {"ci_holds": False}))]
        path = os.path.join(self.dir, "pareto.json")
        with open(path, "w") as f:
            json.dump(rows, f)
        out = os.path.join(self.dir, "p.png")
        r = run_script("pareto_plot.py", path, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        with open(path, "w") as f:
            f.write("[]")
        r = run_script("pareto_plot.py", path, out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no runs", r.stderr)


class Pxpl5WorkloadTest(ScratchTest):
    def stats(self):
        return {"machine": "machine-f", "scene": "s",
                "pxpl5": {"caster_workload": [1.0, 0.5, 0.75], "scheme": "squares",
                          "order": "cost"},
                "modules": {"caster0": {"regions": 4}, "caster1": {"regions": 2},
                            "caster2": {"regions": 3},
                            "ring": {"utilization": 0.25, "bytes.samples": 8e6,
                                     "bytes.band": 8e6, "bytes.pixels": 4e6}}}

    def test_series_and_png(self):
        w, regions, class_bytes, util = pxpl5_workload.workload_series(self.stats())
        self.assertEqual(w, [1.0, 0.5, 0.75])
        self.assertEqual(regions, [4.0, 2.0, 3.0])
        self.assertEqual(class_bytes["pixels"], 4e6)
        self.assertEqual(class_bytes["request"], 0.0)
        self.assertEqual(util, 0.25)
        with open(os.path.join(self.dir, "stats.json"), "w") as f:
            json.dump(self.stats(), f)
        out = os.path.join(self.dir, "p.png")
        r = run_script("pxpl5_workload.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)

    def test_bad_input(self):
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump({"machine": "machine-a"}, f)
        r = run_script("pxpl5_workload.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("caster_workload", r.stderr)


def probe_stats():
    """A latency_probe of two stages: 'queue' (2 us queueing) and 'cpu' (3 us service, 1 us
    transfer), 7 us end to end, so 1 us unattributed."""
    return {"machine": "m", "scene": "s", "latency_probe": {
        "rays": 5,
        "end_to_end_s": {"count": 5, "mean": 7e-6, "p50": 7e-6, "p99": 9e-6, "max": 9e-6},
        "unattributed_s": 1e-6,
        "stages": {
            "queue": {"queueing_s": 2e-6, "service_s": 0.0, "transfer_s": 0.0, "total_s": 2e-6,
                      "p99_s": 3e-6, "share": 2 / 7},
            "cpu": {"queueing_s": 0.0, "service_s": 3e-6, "transfer_s": 1e-6, "total_s": 4e-6,
                    "p99_s": 5e-6, "share": 4 / 7}}}}


class LatencyBreakdownTest(ScratchTest):
    def test_series(self):
        s = latency_breakdown.breakdown_series(probe_stats())
        self.assertEqual(s["stages"], ["queue", "cpu"])  # the order stats.json lists them in
        self.assertEqual(s["queueing"], [2e-6, 0.0])
        self.assertEqual(s["service"], [0.0, 3e-6])
        self.assertEqual(s["transfer"], [0.0, 1e-6])
        self.assertEqual((s["end_to_end_s"], s["unattributed_s"], s["rays"]), (7e-6, 1e-6, 5))

    def test_drawn_bars(self):
        fig, ax, bars = latency_breakdown.draw(
            latency_breakdown.breakdown_series(probe_stats()), "t")
        try:
            # The rectangles matplotlib holds, in microseconds (the unit chosen for 7 us):
            # stacked queueing | service | transfer per stage, then the rest and end to end.
            drawn = {}
            for c in ax.containers:
                for r in c.patches:
                    drawn.setdefault(c.get_label(), []).append(
                        (round(r.get_y() + r.get_height() / 2), r.get_x(), r.get_width()))
            def close(got, want):
                np.testing.assert_allclose(np.asarray(got), np.asarray(want), atol=1e-9)

            close(drawn["queueing"], [(0, 0.0, 2.0), (1, 0.0, 0.0)])
            close(drawn["service"], [(0, 2.0, 0.0), (1, 0.0, 3.0)])
            close(drawn["transfer"], [(0, 2.0, 0.0), (1, 3.0, 1.0)])
            close(drawn["unattributed"], [(2, 0.0, 1.0)])
            (e2e,) = [v for k, v in drawn.items()
                      if k not in ("queueing", "service", "transfer", "unattributed")]
            close(e2e, [(3, 0.0, 7.0)])
            # The stage bars and the rest add up to the end-to-end bar.
            total = sum(w for k in ("queueing", "service", "transfer", "unattributed")
                        for _, _, w in drawn[k])
            self.assertAlmostEqual(total, 7.0, places=9)
            self.assertEqual([t.get_text() for t in ax.get_yticklabels()],
                             ["queue", "cpu", "unattributed", "end to end (mean)"])
            self.assertIn("µs", ax.get_xlabel())
            self.assertEqual(bars["cpu"]["transfer"], (3.0, 1.0))
        finally:
            latency_breakdown.common.pyplot().close(fig)

    def test_command_line_and_bad_input(self):
        path = os.path.join(self.dir, "stats.json")
        with open(path, "w") as f:
            json.dump(probe_stats(), f)
        out = os.path.join(self.dir, "b.png")
        r = run_script("latency_breakdown.py", self.dir, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        with open(path, "w") as f:
            json.dump({"machine": "m", "ray_latency_s": {"count": 1}}, f)
        r = run_script("latency_breakdown.py", path, os.path.join(self.dir, "x.png"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("--latency-probe", r.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "x.png")))


def g_row(rid, title, seed_ref, seed_value, simulated, unit="us", workload="", note="",
          passed=True):
    return {"id": rid, "title": title, "seed_ref": seed_ref, "seed_text": "", "unit": unit,
            "seed_value": seed_value, "simulated_value": simulated, "relative_error": None,
            "tolerance": {"kind": "relative", "value": 0.2}, "pass": passed, "note": note,
            "error": "", "workload": workload}


def gaudet_rows():
    """Rows shaped as `rtsim validate --only P2,P4` writes them (platform/validation/
    gaudet_figures.cpp), with round numbers."""
    def p2(rid, tree, scene, processing, latency):
        return g_row(rid, f"ShellProcessor processing per ray, {tree} ({scene})",
                     "seed 001 L1025-L1030", 467.8, processing,
                     note=f"latency (emerges from the bus) {latency} us per ray, thesis 124.9 "
                          "us; 11.69 boxes tested per ray")
    def p4(rid, other, breadth, values, passed):
        return g_row(rid, f"ShellProcessor latency, {other} over breadth-first (mean of "
                          "404..420)", "seed 001 L1019, L1032-L1039", 2.37, 1.01, unit="ratio",
                     note=f"breadth {breadth} us, other {values} us", passed=passed)
    return [
        # Ullner's G1 (an image identity) must be ignored.
        g_row("G1", "the peripheral's image equals the functional renderer's", "DESIGN.md", 0, 0,
              unit=""),
        p2("P2a", "binary", 212, 500.5, 33.5),
        p2("P2b", "quad", 412, 505.0, 13.66),
        p2("P2c", "oct", 812, 660.0, 1.2e1),
        p4("P4a", "depth-first", "4/6/13/16/18", "4.5/6.5/13.5/16.5/18.5", False),
        p4("P4b", "random", "4/6/13/16/18", "5/7/14/17/19", True),
    ]


class FiguresTest(ScratchTest):
    def test_ullner_model_reproduces_the_seed_minimum(self):
        # L652 with L654's parameters: minimum 14.3 us at n_s = 11 (seed 000 L654), and 1/3 ms
        # plus stepping and latency without subdivision.
        values = {n: figures.ullner_model_us(n) for n in range(1, 31)}
        best = min(values, key=values.get)
        self.assertEqual(best, 11)
        self.assertAlmostEqual(values[11], 14.31, delta=0.01)
        self.assertAlmostEqual(values[1], 1.0 + 1000.0 / 3.0 + 5.6, places=9)
        self.assertAlmostEqual(figures.ullner_model_intersections(1), 1000.0)

    def test_gaudet_values_are_read_from_the_rows_validate_writes(self):
        with open(os.path.join(self.dir, "validation.json"), "w") as f:
            json.dump({"rows": gaudet_rows()}, f)
        val = figures.Validation(self.dir)
        self.assertEqual(figures.gaudet_fig610(val), {
            "binary": {"processing": 500.5, "latency": 33.5},
            "quad": {"processing": 505.0, "latency": 13.66},
            "oct": {"processing": 660.0, "latency": 12.0}})
        fig611 = figures.gaudet_fig611(val)
        self.assertEqual(len(fig611), 15)
        self.assertEqual(fig611[(404, "breadth")], 4.0)
        self.assertEqual(fig611[(420, "breadth")], 18.0)
        self.assertEqual(fig611[(408, "depth")], 6.5)
        self.assertEqual(fig611[(416, "random")], 17.0)
        # P4a fails: the figure says it is not reproduced.
        self.assertEqual(figures.gaudet_order_verdict(val), "NOT reproduced (P4a fails)")
        self.assertEqual(figures.gaudet_speedup(val), {})

        # Kept run folders are read first (exact values rather than the notes' 4 digits).
        run = os.path.join(self.dir, "runs-x", "pert-412-adaptive-breadth-n1")
        os.makedirs(run)
        with open(os.path.join(run, "stats.json"), "w") as f:
            json.dump({"gaudet": {"shell": {"processing_per_ray_s": 5.1e-4,
                                            "latency_per_ray_s": 1.25e-5}}}, f)
        val = figures.Validation(self.dir)
        quad = figures.gaudet_fig610(val)["quad"]
        self.assertAlmostEqual(quad["processing"], 510.0)
        self.assertAlmostEqual(quad["latency"], 12.5)
        self.assertAlmostEqual(figures.gaudet_fig611(val)[(412, "breadth")], 12.5)
        self.assertEqual(figures.gaudet_fig611(val)[(412, "depth")], 13.5)

    def test_speedup_curves_from_gaudet_speedup_csv(self):
        with open(os.path.join(self.dir, "gaudet-speedup.csv"), "w") as f:
            f.write("scene,mode,pert_count,frame_s,vax_frame_s,speedup_over_vax\n")
            for mode, t1 in (("direct", 3.5), ("non-adaptive", 9.4), ("adaptive", 3.8)):
                for n in (8, 1, 64):  # out of order: sorted by the count
                    f.write(f"412,{mode},{n},{t1 / n},63.9,{63.9 / (t1 / n)}\n")
        val = figures.Validation(self.dir)
        curves = figures.gaudet_speedup(val)
        self.assertEqual(list(curves), ["412"])
        self.assertEqual(sorted(curves["412"]), ["adaptive", "direct", "non-adaptive"])
        ns, ys = curves["412"]["direct"]
        np.testing.assert_allclose(ns, [1, 8, 64])
        np.testing.assert_allclose(ys, [63.9 / 3.5, 8 * 63.9 / 3.5, 64 * 63.9 / 3.5])
        out = os.path.join(self.dir, "speedup.png")
        r = run_script("figures.py", self.dir, out, "--figure", "speedup")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        with open(os.path.join(self.dir, "gaudet-speedup.csv"), "w") as f:
            f.write("scene,pert_count\n412,1\n")
        r = run_script("figures.py", self.dir, out, "--figure", "speedup")
        self.assertEqual(r.returncode, 2)
        self.assertIn("gaudet-speedup.csv: expected the columns", r.stderr)

    def make_validation(self, with_gaudet):
        rows = [g_row("V8b", "Fig. 2-18, analytic model: minimum", "seed 000 L654", 14.3, 14.31),
                g_row("VAX3", "T_i recovered", "seed 001 L317", 429, 429.0),
                g_row("VAX4", "T_s recovered", "seed 001 L318", 710, 710.0)]
        if with_gaudet:
            rows += gaudet_rows()
        with open(os.path.join(self.dir, "validation.json"), "w") as f:
            json.dump({"rows": rows}, f)
        with open(os.path.join(self.dir, "fig2-18.csv"), "w") as f:
            f.write("n_s,model_t_r_us,simulated_t_r_us,model_intersections_per_ray,"
                    "simulated_tests_per_ray,model_t_r_measured_d_r_us\n")
            for n in (1, 4, 11, 30):
                f.write(f"{n},{figures.ullner_model_us(n)},{figures.ullner_model_us(n) * 1.1},"
                        f"{figures.ullner_model_intersections(n)},20,"
                        f"{figures.ullner_model_us(n)}\n")
        run = os.path.join(self.dir, "runs-abc123", "vax-default")
        os.makedirs(run)
        with open(os.path.join(run, "stats.json"), "w") as f:
            json.dump({"rays": {"total": 100}, "scene_stats": {"primitives": 10},
                       "simulated_time_s": 100 * (710e-6 + 10 * 429e-6)}, f)

    def test_series_read_from_a_validation_folder(self):
        self.make_validation(with_gaudet=True)
        val = figures.Validation(self.dir)
        s = figures.series_fig218(val)
        np.testing.assert_allclose(s["simulated"][0], [1, 4, 11, 30])
        np.testing.assert_allclose(s["simulated"][1],
                                   [figures.ullner_model_us(n) * 1.1 for n in (1, 4, 11, 30)])
        points, rec = figures.series_vax(val)
        self.assertEqual(len(points), 1)
        self.assertAlmostEqual(points[0][0], 10)
        self.assertAlmostEqual(points[0][1], 0.710 + 10 * 0.429)  # ms per ray
        self.assertEqual(rec, {"t_i_us": 429.0, "t_s_us": 710.0})
        self.assertEqual(figures.gaudet_fig610(val)["quad"], {"processing": 505.0,
                                                               "latency": 13.66})

    def test_command_line_draws_what_there_is(self):
        self.make_validation(with_gaudet=False)
        out = os.path.join(self.dir, "all.png")
        each = os.path.join(self.dir, "each")
        r = run_script("figures.py", self.dir, out, "--each", each)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out, 800, 800)
        # No cubes runs and no gaudet-speedup.csv: Fig 2-19 and the speed-up curves are skipped
        # with a note; the Gaudet tables are drawn from the thesis alone.
        self.assertIn("fig2-19: no data", r.stderr)
        self.assertIn("speedup: no data", r.stderr)
        drawn = sorted(os.listdir(each))
        self.assertEqual(drawn, ["fig2-18.png", "fig2-21.png", "fig6-10.png", "fig6-11.png",
                                 "summary.png", "vax.png"])
        for name in drawn:
            self.assertGoodPng(os.path.join(each, name))
        r = run_script("figures.py", self.dir, out, "--figure", "fig9-99")
        self.assertEqual(r.returncode, 2)

    def test_fig610_marks_the_sensitivity_settings(self):
        self.make_validation(with_gaudet=True)
        sens = os.path.join(self.dir, "sensitivity.json")
        trees = {s: {"processing_us": 500.0, "latency_us": lat, "starved_us": 0.0}
                 for s, lat in (("212", 80.5), ("412", 5.15), ("812", 0.72))}
        with open(sens, "w") as f:
            json.dump({"size": 40, "settings": [{"setting": "one ray", "trees": trees}]}, f)
        out = os.path.join(self.dir, "fig610.png")
        r = run_script("figures.py", self.dir, out, "--figure", "fig6-10", "--sensitivity", sens)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGoodPng(out)
        with open(sens, "w") as f:
            json.dump({"rows": []}, f)
        r = run_script("figures.py", self.dir, out, "--figure", "fig6-10", "--sensitivity", sens)
        self.assertEqual(r.returncode, 2)
        self.assertIn("gaudet_sensitivity.py", r.stderr)


class ReadableAxesTest(ScratchTest):
    """What a reader sees on the axes (issue 18, item 4): several labelled ticks on a log axis,
    reaching below the data's minimum; no offset or multiplier text; whole numbers on axes of
    counts; times in one unit named in the label; legends in the order of their values, off
    the data. Checked on the matplotlib objects as drawn."""

    def write_sweep(self):
        """pert_count 1..5 for three bit times written as text, sorting as text would put
        "1000 ns" first; frame times differing in the sixth digit (an offset on a plain axis)
        and times per ray from 15 to 414 us (one decade mark, 1e-4, on a plain log axis)."""
        path = os.path.join(self.dir, "results.jsonl")
        with open(path, "w") as f:
            for bit_time, k in (("1000 ns", 4), ("250 ns", 1), ("500 ns", 2)):
                for n in range(1, 6):
                    f.write(json.dumps({
                        "pert_count": n, "link.bit_time": bit_time, "status": "ok",
                        "simulated_time_s": 8.804e-2 + 1e-7 * (n + k),
                        "peripheral.time_per_ray_s": 15e-6 * k * (6 - n) ** 1.2}) + "\n")
        return path

    def drawn(self, *argv):
        """(fig, ax) of sweep_plot with these options on the sweep, rendered."""
        args = sweep_plot.parse_args([self.write_sweep(), os.path.join(self.dir, "x.png"),
                                      *argv])
        fig, ax = sweep_plot.figure(args)
        self.addCleanup(common.pyplot().close, fig)
        fig.canvas.draw()
        return fig, ax

    def labels(self, axis):
        """The tick labels shown: those with text at ticks within the view."""
        lo, hi = sorted(axis.get_view_interval())
        tol = 1e-9 * max(abs(lo), abs(hi))
        return [t.get_text() for t, v in zip(axis.get_majorticklabels(),
                                             axis.get_majorticklocs())
                if t.get_text() and lo - tol <= v <= hi + tol]

    def assertNoOffsetText(self, ax):
        for axis in (ax.xaxis, ax.yaxis):
            self.assertEqual(axis.get_offset_text().get_text(), "", axis.axis_name)

    def assertTimeLabel(self, label):
        self.assertRegex(label, r"\((ns|µs|ms|s|h)\)")

    def assertLegendClear(self, fig, ax):
        """The legend hides no line vertex (marker) of the axes."""
        box = ax.get_legend().get_window_extent(fig.canvas.get_renderer())
        for line in ax.lines:
            xy = line.get_transform().transform(line.get_xydata())
            inside = ((xy[:, 0] > box.x0) & (xy[:, 0] < box.x1) & (xy[:, 1] > box.y0)
                      & (xy[:, 1] < box.y1))
            self.assertFalse(inside.any(), f"the legend hides {line.get_label()}")

    def test_sweep_plot_log_axis_of_times(self):
        fig, ax = self.drawn("--x", "pert_count", "--y", "peripheral.time_per_ray_s", "--logy",
                             "--group", "link.bit_time", "--ylabel", "time per ray (s)")
        labels = self.labels(ax.yaxis)
        self.assertGreaterEqual(len(labels), 3, labels)
        # The lowest label is at or below the smallest value: the minimum can be read.
        lowest = min(float(t) for t in labels)
        self.assertLessEqual(lowest, min(line.get_ydata().min() for line in ax.lines))
        self.assertEqual(ax.get_ylabel(), "time per ray (µs)")
        self.assertNoOffsetText(ax)
        for t in self.labels(ax.xaxis):
            self.assertRegex(t, r"^\d+$")  # pert_count: whole numbers only
        self.assertEqual([t.get_text() for t in ax.get_legend().get_texts()],
                         ["250 ns", "500 ns", "1000 ns"])
        self.assertLegendClear(fig, ax)

    def test_sweep_plot_close_times_and_a_time_on_x(self):
        fig, ax = self.drawn("--x", "pert_count", "--y", "simulated_time_s", "--group", "none")
        self.assertTimeLabel(ax.get_ylabel())
        self.assertNoOffsetText(ax)
        # In ms: pert_count 1 averaged over the three bit times (k = 4, 1, 2).
        np.testing.assert_allclose(ax.lines[0].get_ydata()[0], 88.04 + 1e-4 * (1 + 7 / 3))
        fig, ax = self.drawn("--x", "link.bit_time", "--y", "simulated_time_s", "--group",
                             "pert_count")
        self.assertEqual(ax.get_xlabel(), "link.bit_time (µs)")  # "250 ns" read as a time
        np.testing.assert_allclose(ax.lines[0].get_xdata(), [0.25, 0.5, 1.0])
        self.assertNoOffsetText(ax)
        self.assertEqual([t.get_text() for t in ax.get_legend().get_texts()],
                         ["1", "2", "3", "4", "5"])

    def write_lines(self, values):
        """A sweep of x = 1..10 with one group per entry of `values`: group g's y at x is
        values[g](x)."""
        path = os.path.join(self.dir, "lines.jsonl")
        with open(path, "w") as f:
            for g, fn in enumerate(values):
                for x in range(1, 11):
                    f.write(json.dumps({"x": x, "group": f"g{g}", "status": "ok",
                                        "simulated_time_s": fn(x)}) + "\n")
        return path

    def drawn_lines(self, values):
        args = sweep_plot.parse_args([self.write_lines(values), os.path.join(self.dir, "l.png"),
                                      "--x", "x", "--y", "simulated_time_s", "--group", "group"])
        fig, ax = sweep_plot.figure(args)
        self.addCleanup(common.pyplot().close, fig)
        fig.canvas.draw()
        return fig, ax

    def test_equal_lines_are_told_apart(self):
        # g1 equals g0 (link and link_in of the sweep report's utilisation): drawn dashed over
        # it with a marker of its own, and its legend entry says so.
        fig, ax = self.drawn_lines([lambda x: x, lambda x: x, lambda x: 2 * x])
        texts = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertEqual(texts, ["g0", "g1 (= g0)", "g2"])
        self.assertEqual(ax.lines[0].get_linestyle(), "-")
        self.assertEqual(ax.lines[1].get_linestyle(), "--")
        self.assertNotEqual(ax.lines[0].get_marker(), ax.lines[1].get_marker())

    def test_many_lines_put_the_legend_below_not_beside(self):
        # Eight lines across the whole axes: no place inside is free. Beside the axes the
        # legend widened the PNG by its width; below them, in columns, it does not.
        fig, ax = self.drawn_lines([(lambda g: (lambda x: g + 0.3 * (x % 3)))(g)
                                    for g in range(8)])
        renderer = fig.canvas.get_renderer()
        box = ax.get_legend().get_window_extent(renderer)
        self.assertLess(box.y1, ax.xaxis.get_tightbbox(renderer).y0)  # under the x label
        self.assertLessEqual(box.x1, fig.bbox.x1)
        self.assertGreaterEqual(box.x0, fig.bbox.x0)

    def test_time_axes_of_a_run(self):
        edges, busy, depth = utilisation_timeline.busy_from_trace(make_trace(), windows=4)
        fig, axes = utilisation_timeline.draw({k: (edges, v) for k, v in busy.items()},
                                              {k: (edges, v) for k, v in depth.items()}, "t")
        self.addCleanup(common.pyplot().close, fig)
        fig.canvas.draw()
        self.assertTimeLabel(axes[-1].get_xlabel())
        self.assertIn("(µs)", axes[-1].get_xlabel())
        self.assertLessEqual(axes[-1].get_xlim()[1], 42.0)  # 40 us drawn as 40
        for ax in axes:
            self.assertNoOffsetText(ax)
            self.assertLegendClear(fig, ax)
        fig, ax = latency_histogram.draw([1e-6, 2e-6, 4e-6, 8e-6], [1, 4, 2],
                                         {"mean": 2.5e-6, "p99": 4e-6}, 7, "t")
        self.addCleanup(common.pyplot().close, fig)
        fig.canvas.draw()
        self.assertEqual(ax.get_xlabel(), "ray latency (µs)")
        self.assertGreaterEqual(len(self.labels(ax.xaxis)), 3)
        for t in self.labels(ax.yaxis):
            self.assertRegex(t, r"^\d+$")  # a count of rays
        self.assertNoOffsetText(ax)
        self.assertLegendClear(fig, ax)

    def test_helpers(self):
        self.assertEqual(sorted(["1000 ns", "250 ns", "1 ms", "builtin:npp-16", "500 ns",
                                 "builtin:npp-8"], key=common.value_order_key),
                         ["250 ns", "500 ns", "1000 ns", "1 ms", "builtin:npp-8",
                          "builtin:npp-16"])
        self.assertEqual(common.time_unit(88e-3), (1e3, "ms"))
        self.assertEqual(common.time_unit(7200.0)[1], "h")
        self.assertEqual(common.label_with_unit("ray latency (s)", "µs"), "ray latency (µs)")
        for lo, hi in ((15.0, 300.0), (14.0, 18.0), (1e-5, 1.0), (0.9, 1.1)):
            ticks = common.log_ticks(lo, hi)
            self.assertLessEqual(ticks[0], lo)
            self.assertGreaterEqual(ticks[-1], hi)
            self.assertGreaterEqual(np.count_nonzero((ticks >= lo) & (ticks <= hi)), 2)


class ManyModulesTest(unittest.TestCase):
    """A machine of many instances (gaudet-pert's 64 PERTs) draws a line per class of module,
    its mean with a min-max band, not a line and a legend entry per instance."""

    def test_instances_of_a_class_become_one_group(self):
        edges = [0.0, 1.0, 2.0]
        series = {f"pert{i}.shell": (edges, [0.5 + 0.01 * i, 0.6]) for i in range(14)}
        series["shell_bus"] = (edges, [0.3, 0.4])
        groups = utilisation_timeline.module_groups(series)
        self.assertEqual(sorted(groups), ["pert*.shell (14: mean, min-max)", "shell_bus"])
        _, mean, low, high = groups["pert*.shell (14: mean, min-max)"]
        self.assertAlmostEqual(mean[0], 0.565)
        self.assertAlmostEqual(low[0], 0.5)
        self.assertAlmostEqual(high[0], 0.63)
        self.assertIsNone(groups["shell_bus"][2])
        # Few series: each its own line.
        few = {k: series[k] for k in list(series)[:5]}
        self.assertEqual(sorted(utilisation_timeline.module_groups(few)), sorted(few))

    def test_times_read_in_their_own_unit(self):
        self.assertEqual(common.seconds_text(0.0026268), "2.627 ms")
        self.assertEqual(common.seconds_text(9.573e-6), "9.573 µs")
        self.assertEqual(common.seconds_text(0.0), "0 s")


@unittest.skipUnless(os.environ.get("RTSIM_BINARY"), "RTSIM_BINARY not set")
class RealRunTest(unittest.TestCase, PngMixin):
    """A real run: the trace and stats.json windows must tell the same story."""

    def test_trace_and_stats_agree_on_utilisation(self):
        out = tempfile.mkdtemp(prefix="rtsim-analysis-run-")
        try:
            r = subprocess.run([os.environ["RTSIM_BINARY"], "run", "--width", "16", "--height",
                                "16", "--trace", "perfetto", "--latency-probe", "-q", "--out",
                                out],
                               capture_output=True, text=True, timeout=300)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "stats.json")) as f:
                stats = json.load(f)
            edges, series = utilisation_timeline.busy_from_stats(stats)
            for name, (e, values) in series.items():
                m = stats["modules"][name]
                # The windows add up to the module's busy time and average to its utilisation.
                self.assertAlmostEqual(float(np.sum(values)) * (e[1] - e[0]), m["busy_s"],
                                       delta=1e-9 + 1e-6 * m["busy_s"])
                self.assertAlmostEqual(float(np.mean(values)), m["utilization"], delta=1e-6)
            tedges, busy, depth = utilisation_timeline.busy_from_trace(
                utilisation_timeline.load(os.path.join(out, "trace.json"))[1], windows=100)
            self.assertIn("peripheral.ray_queue.depth", depth)
            # Every module's busy counter is its busy intervals: the same busy time as
            # stats.json, over the window the trace covers (from 0 to the end of the frame).
            for name, m in stats["modules"].items():
                if "queue" in m:
                    self.assertIn(name + ".depth", depth)
                    continue
                if "busy_s" not in m:  # a group of counters only ("peripheral": rays served)
                    self.assertNotIn(name, busy)
                    continue
                trace_busy = float(np.sum(busy[name]) * (tedges[1] - tedges[0]))
                self.assertAlmostEqual(trace_busy, m["busy_s"], delta=1e-9 * m["busy_s"] + 1e-15,
                                       msg=name)
            # The probe's breakdown as drawn adds up to the end-to-end mean, which is the mean
            # of ray_latency_s (the same rays over the same window).
            series = latency_breakdown.breakdown_series(stats)
            drawn = sum(sum(series[p]) for p in latency_breakdown.PARTS)
            drawn += series["unattributed_s"]
            self.assertAlmostEqual(drawn, stats["ray_latency_s"]["mean"],
                                   delta=1e-9 * stats["ray_latency_s"]["mean"])
            for script, args in (("utilisation_timeline.py", [out]),
                                 ("latency_histogram.py", [os.path.join(out, "stats.json")]),
                                 ("latency_breakdown.py", [out])):
                png = os.path.join(out, script.replace(".py", ".png"))
                r = run_script(script, *args, png)
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertGoodPng(png)
        finally:
            shutil.rmtree(out)


if __name__ == "__main__":
    unittest.main(verbosity=2)
