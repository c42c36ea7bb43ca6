// `rtsim run --latency-probe` on vax-750 and ullner-peripheral: the probe changes nothing else
// (image and every other stats.json key identical to a run without it), it covers the same
// rays over the same window as ray_latency_s, every wait and piece of work is attributed to a
// stage (unattributed ~ 0), the stage sums agree with figures measured independently (the
// peripheral's time per ray, the grid walk, Little's law on the queues), and the breakdown
// moves the way a what-if says it must (a deeper ray queue, a slower host).
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
/// Keys in file order: the probe lists its stages in the order a ray meets them.
using json = nlohmann::ordered_json;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

namespace {

/// Unattributed time per ray, relative to the end-to-end mean. Both machines attribute every
/// interval of the window exactly (the parts add up, in integer picoseconds, to the window);
/// what remains is the rounding of summing the parts as doubles in seconds (~1e-16 of the
/// latency per ray). 1e-12 leaves room for that and catches a forgotten stage: the smallest
/// real part on these runs (one fetch stage, 333 ns) is 1e-4 of the mean.
constexpr double kUnattributedTolerance = 1e-12;

struct Run {
  fs::path dir;
  json stats;
};

Run run_ok(const std::string& tag, const std::string& args) {
  Run r;
  r.dir = scratch_dir(tag);
  const auto res = run_rtsim("run " + args + " -q --out " + r.dir.string());
  EXPECT_EQ(res.exit_code, 0) << args << "\n" << res.output;
  if (res.exit_code == 0) r.stats = read_json(r.dir / "stats.json");
  return r;
}

/// The stats without the wall-clock keys (the only ones that differ between two runs).
json without_wall_clock(json s) {
  s.erase("wall_time_s");
  s.erase("rays_per_second");
  return s;
}

double stage(const json& probe, const std::string& name, const std::string& part) {
  EXPECT_TRUE(probe["stages"].contains(name)) << name << " in " << probe["stages"].dump();
  return probe["stages"]
      .value(name, json::object())
      .value(part, std::numeric_limits<double>::quiet_NaN());
}

/// Runs `args` with and without the probe and checks what must hold on any machine; returns
/// the probed run's stats.
json check_probe_changes_nothing_and_covers_the_window(const std::string& tag,
                                                       const std::string& args) {
  const Run off = run_ok(tag + "-off", args);
  const Run on = run_ok(tag + "-on", args + " --latency-probe");
  if (off.stats.is_null() || on.stats.is_null()) return json();
  // The image is the same bit for bit; stats.json only gains latency_probe.
  for (const char* f : {"image.png", "image.exr"})
    EXPECT_EQ(read_file(off.dir / f), read_file(on.dir / f)) << tag << " " << f;
  EXPECT_FALSE(off.stats.contains("latency_probe"));
  EXPECT_TRUE(on.stats.contains("latency_probe"));
  json rest = on.stats;
  rest.erase("latency_probe");
  EXPECT_EQ(without_wall_clock(rest), without_wall_clock(off.stats)) << tag;

  const json& probe = on.stats["latency_probe"];
  const json& lat = on.stats["ray_latency_s"];
  // The same rays over the same window: every ray of ray_latency_s has a journey.
  EXPECT_EQ(probe["rays"], lat["count"]);
  EXPECT_EQ(probe["rays"], on.stats["rays"]["total"]);
  const double mean = lat["mean"].get<double>();
  const double e2e = probe["end_to_end_s"]["mean"].get<double>();
  EXPECT_NEAR(e2e, mean, 1e-12 * mean);
  // The journey starts are kept in integer time, so the samples are the same numbers.
  EXPECT_EQ(probe["end_to_end_s"], lat);
  const double rest_s = probe["unattributed_s"].get<double>();
  std::cout << tag << ": " << probe["rays"] << " rays, end-to-end mean " << e2e
            << " s, unattributed " << rest_s << " s (" << std::abs(rest_s) / e2e
            << " of it; tolerance " << kUnattributedTolerance << ")\n";
  EXPECT_LE(std::abs(rest_s), kUnattributedTolerance * e2e);
  // The stage totals and the rest add up to the end-to-end mean; shares add up to 1 - rest.
  double sum = 0.0, shares = 0.0;
  for (const auto& [name, st] : probe["stages"].items()) {
    const double parts = st["queueing_s"].get<double>() + st["service_s"].get<double>() +
                         st["transfer_s"].get<double>();
    EXPECT_NEAR(st["total_s"].get<double>(), parts, 1e-12 * e2e) << name;
    for (const char* p : {"queueing_s", "service_s", "transfer_s"})
      EXPECT_GE(st[p].get<double>(), 0.0) << name << " " << p;
    EXPECT_LE(st["p99_s"].get<double>(), lat["max"].get<double>() * (1 + 1e-12)) << name;
    sum += parts;
    shares += st["share"].get<double>();
  }
  EXPECT_NEAR(sum + rest_s, e2e, 1e-12 * e2e);
  EXPECT_NEAR(shares, 1.0, 1e-9);
  return on.stats;
}

/// Little's law on a queue: its time-weighted mean occupancy over the frame times the frame
/// time is the total time rays spent in it.
double littles_time_per_ray(const json& s, const std::string& queue) {
  const json& m = s["modules"][queue];
  return m["queue"]["mean_occupancy"].get<double>() * s["simulated_time_s"].get<double>() /
         s["rays"]["total"].get<double>();
}

const std::string kCubes = "--machine ullner-peripheral --scene builtin:ullner-cubes ";

}  // namespace

TEST(LatencyProbeRun, VaxIsAllServiceAtTheVax) {
  const json s = check_probe_changes_nothing_and_covers_the_window(
      "probe-vax", "--machine vax-750 --scene " + shared_path("scenes/balls-s1.nff") +
                       " --width 16 --height 16");
  ASSERT_FALSE(s.is_null());
  const json& p = s["latency_probe"];
  ASSERT_EQ(p["stages"].size(), 1u);
  // Each ray: T_s + O T_i of work on the one processor (seed 001 L326), no queue, no bus.
  const double per_ray = 710e-6 + 429e-6 * s["scene_stats"]["primitives"].get<double>();
  EXPECT_NEAR(stage(p, "vax", "service_s"), per_ray, 1e-12);
  EXPECT_EQ(stage(p, "vax", "queueing_s"), 0.0);
  EXPECT_EQ(stage(p, "vax", "transfer_s"), 0.0);
  EXPECT_EQ(p["unattributed_s"], 0.0);
}

TEST(LatencyProbeRun, PeripheralBruteForceStagesMatchTheMachinesOwnFigures) {
  const json s = check_probe_changes_nothing_and_covers_the_window(
      "probe-brute", kCubes + "--width 24 --height 24");
  ASSERT_FALSE(s.is_null());
  const json& p = s["latency_probe"];
  std::vector<std::string> names;
  for (const auto& [name, st] : p["stages"].items()) names.push_back(name);
  // In the order a ray meets them; no auxiliary processor without the grid.
  EXPECT_EQ(names, (std::vector<std::string>{"host.ray_link", "peripheral.ray_queue",
                                             "peripheral.parameter_memories", "peripheral.pipeline",
                                             "peripheral.result_link", "host.result_queue"}));
  // The peripheral's own time per ray (Ullner's t_r) is its stages' service: the fetch stage
  // ahead of the first polygon and the pipe (n_p polygons, its depth, the selection).
  const double t_r = s["peripheral"]["time_per_ray_s"].get<double>();
  const double fetch = stage(p, "peripheral.parameter_memories", "service_s");
  const double pipe = stage(p, "peripheral.pipeline", "service_s");
  EXPECT_NEAR(fetch + pipe, t_r, 1e-12 * t_r);
  EXPECT_NEAR(fetch, 333.333e-9, 1e-15);  // one fetch stage of one intersect interval
  const double n = s["peripheral"]["polygons"].get<double>();
  EXPECT_NEAR(pipe, (n - 1 + 17 + 1) * 333.333e-9, 1e-12);  // (n_p - 1) t_i + t_l + select
  // The ray queue and the result queue: what the probe says a ray waited there is what their
  // occupancy says (Little's law); the result queue never filled here, so no ray waited for
  // room in it either.
  const double rq = stage(p, "peripheral.ray_queue", "queueing_s");
  EXPECT_NEAR(rq, littles_time_per_ray(s, "peripheral.ray_queue"), 1e-9 * rq);
  const json& hq = s["modules"]["host.result_queue"]["queue"];
  ASSERT_LT(hq["max_occupancy"].get<int>(), hq["capacity"].get<int>());
  const double res_q = stage(p, "host.result_queue", "queueing_s");
  EXPECT_NEAR(res_q, littles_time_per_ray(s, "host.result_queue"), 1e-9 * res_q);
  // Wire time: the RayResult's 8 words cross the result link a word per 1/3 us; the TraceRay's
  // 7 cross the ray link while the host writes them (no later than its last write), so none
  // of its time is the link's. Nothing else is a transfer.
  for (const auto& [name, st] : p["stages"].items()) {
    const double want = name == "peripheral.result_link" ? 8 * 333.333e-9 : 0.0;
    EXPECT_NEAR(st["transfer_s"].get<double>(), want, 1e-15) << name;
  }
}

TEST(LatencyProbeRun, PeripheralGridAddsTheAuxiliaryProcessorsWalk) {
  const json s = check_probe_changes_nothing_and_covers_the_window(
      "probe-grid", kCubes + "--width 24 --height 24 -p peripheral.grid.divisions=6");
  ASSERT_FALSE(s.is_null());
  const json& p = s["latency_probe"];
  ASSERT_EQ(std::next(p["stages"].begin()).key(), "peripheral.ray_queue");  // after the ray link
  // Walk n_d t_d (t_d = 1 us, seed 000 L654) and one indirection stage per ray.
  const double walk = s["peripheral"]["subvolumes_visited_per_ray"].get<double>() * 1e-6;
  EXPECT_NEAR(stage(p, "peripheral.aux", "service_s"), walk + 333.333e-9, 1e-12);
  // Ullner's t_r = n_d t_d + n_i t_i + t_l: the peripheral stages' service together.
  const double t_r = s["peripheral"]["time_per_ray_s"].get<double>();
  const double service = stage(p, "peripheral.aux", "service_s") +
                         stage(p, "peripheral.parameter_memories", "service_s") +
                         stage(p, "peripheral.pipeline", "service_s");
  EXPECT_NEAR(service, t_r, 1e-12 * t_r);
  const double rq = stage(p, "peripheral.ray_queue", "queueing_s");
  EXPECT_NEAR(rq, littles_time_per_ray(s, "peripheral.ray_queue"), 1e-9 * rq);
}

TEST(LatencyProbeRun, DeeperRayQueueMeansLongerQueueingNotMoreService) {
  // Brute force keeps the peripheral the bottleneck (t_r ~ 172 us against a few us of host
  // work per ray), so the ray queue stays full: a ray entering it waits for the D - 1 rays
  // ahead of it and the rest of the one in service, at most D t_r (every ray takes the same
  // t_r in brute force). The first rays find the queue filling, and the host refills a slot
  // only after the result it is shading, so the mean is a little lower: at least 0.8 D t_r
  // (measured 0.88 for D = 2 and 0.92 for D = 32 at 16x16).
  const std::string base = kCubes + "--width 16 --height 16 --latency-probe ";
  json q[2];
  const int depth[2] = {2, 32};
  for (int i = 0; i < 2; ++i) {
    q[i] = run_ok("probe-depth" + std::to_string(depth[i]),
                  base + "-p peripheral.ray_queue_depth=" + std::to_string(depth[i]))
               .stats;
    ASSERT_FALSE(q[i].is_null());
  }
  const double t_r = q[0]["peripheral"]["time_per_ray_s"].get<double>();
  for (int i = 0; i < 2; ++i) {
    const double wait = stage(q[i]["latency_probe"], "peripheral.ray_queue", "queueing_s");
    std::cout << "ray queue depth " << depth[i] << ": queueing " << wait / t_r << " t_r\n";
    EXPECT_GE(wait, 0.8 * depth[i] * t_r);
    EXPECT_LE(wait, depth[i] * t_r * (1 + 1e-12));
  }
  EXPECT_GT(stage(q[1]["latency_probe"], "peripheral.ray_queue", "queueing_s"),
            10 * stage(q[0]["latency_probe"], "peripheral.ray_queue", "queueing_s"));
  EXPECT_EQ(q[1]["latency_probe"]["stages"]["peripheral.pipeline"]["service_s"],
            q[0]["latency_probe"]["stages"]["peripheral.pipeline"]["service_s"]);
}

TEST(LatencyProbeRun, SlowerHostMeansLongerWaitInTheResultQueue) {
  // With the grid the host is the bottleneck (~100% busy): halving its clock leaves the
  // answers waiting for task 2 in the result queue about twice as long, while the
  // peripheral's own stages do not change.
  const std::string base =
      kCubes + "--width 16 --height 16 -p peripheral.grid.divisions=6 --latency-probe ";
  const json fast = run_ok("probe-host5", base + "-p host.clock=5MHz").stats;
  const json slow = run_ok("probe-host2.5", base + "-p host.clock=2.5MHz").stats;
  ASSERT_FALSE(fast.is_null());
  ASSERT_FALSE(slow.is_null());
  const double f = stage(fast["latency_probe"], "host.result_queue", "queueing_s");
  const double w = stage(slow["latency_probe"], "host.result_queue", "queueing_s");
  std::cout << "host.result_queue queueing: 5 MHz host " << f << " s, 2.5 MHz host " << w << " s\n";
  EXPECT_GT(w, 1.5 * f);
  EXPECT_LT(w, 2.5 * f);
  for (const char* st : {"peripheral.aux", "peripheral.parameter_memories", "peripheral.pipeline"})
    EXPECT_DOUBLE_EQ(stage(slow["latency_probe"], st, "service_s"),
                     stage(fast["latency_probe"], st, "service_s"))
        << st;
}

TEST(LatencyProbeRun, EverythingIsAttributedAtALargeQuantumToo) {
  // Temporal decoupling (here 1 ms, far more than a ray's latency) changes the timing the
  // machine computes, not the bookkeeping: the parts still cover the window exactly.
  const json s = check_probe_changes_nothing_and_covers_the_window(
      "probe-quantum",
      kCubes + "--width 16 --height 16 -p peripheral.grid.divisions=6 --quantum \"1 ms\"");
  ASSERT_FALSE(s.is_null());
  // host.ray_link, ray_queue, aux, parameter_memories, pipeline, result_link, result_queue.
  EXPECT_EQ(s["latency_probe"]["stages"].size(), 7u);
}

TEST(LatencyProbeRun, HelpSaysWhatItRecordsAndWhere) {
  const auto r = run_rtsim("run --help");
  EXPECT_EQ(r.exit_code, 0);
  const std::size_t at = r.output.find("--latency-probe");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string text = r.output.substr(at, 400);
  for (const char* word : {"queueing", "service", "transfer", "stats.json", "latency_probe"})
    EXPECT_NE(text.find(word), std::string::npos) << word << " in " << text;
}
