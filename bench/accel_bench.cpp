// Acceleration structures: Ullner's grid (build, DDA steps per second, closest-hit rays per
// second) and Gaudet's shell tree (build, ShellTask+PrimTask rays per second), single thread.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "firmware/accel/dda.hpp"
#include "firmware/accel/grid_divisions.hpp"
#include "firmware/accel/grid_traversal.hpp"
#include "firmware/accel/shell_traversal.hpp"
#include "firmware/accel/shell_tree.hpp"
#include "firmware/accel/uniform_grid.hpp"
#include "tests/kernel_test_support.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::accel;

struct Sphere {
  Vec3 c;
  double r;
};

std::vector<Bounds> random_boxes(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Bounds> out(n);
  const double size = 0.5 / std::cbrt(static_cast<double>(n));
  for (Bounds& b : out) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const Vec3 h(size * u(rng), size * u(rng), size * u(rng));
    b = Bounds{c - h, c + h};
  }
  return out;
}

/// Rays from random points around the unit cube toward random points inside it.
std::vector<Ray> random_rays(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 2.0), v(0.0, 1.0);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    r.origin = Vec3(u(rng), u(rng), u(rng));
    r.direction = glm::normalize(Vec3(v(rng), v(rng), v(rng)) - r.origin + Vec3(1e-9));
  }
  return rays;
}

void BM_GridBuild(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<Bounds> boxes = random_boxes(n, 1);
  const Bounds scene = Bounds{Vec3(0.0), Vec3(1.0)};
  const GridDivisions d = choose_divisions(scene, n);
  for (auto _ : state) {
    UniformGrid g(boxes, scene, d);
    benchmark::DoNotOptimize(g.reference_count());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["cells"] = static_cast<double>(d.cells());
}
BENCHMARK(BM_GridBuild)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

/// Pure DDA walk (void visitor) through an n^3 grid: steps per second.
void BM_DdaSteps(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto variant = static_cast<DdaVariant>(state.range(1));
  const UniformGrid g({}, Bounds{Vec3(0.0), Vec3(1.0)}, {n, n, n});
  const Dda dda(g, variant);
  const std::vector<Ray> rays = random_rays(4096, 2);
  std::uint64_t steps = 0, cells = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const Ray& r = rays[i++ & 4095];
    const DdaResult res =
        dda.traverse(r, 0.0, kInfinity, [](const CellIndex&, auto, double, double) {});
    steps += res.steps;
    cells += res.cells_visited;
  }
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["steps/ray"] =
      static_cast<double>(steps) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetLabel(variant == DdaVariant::Corrected ? "corrected" : "as-printed");
  benchmark::DoNotOptimize(cells);
}
BENCHMARK(BM_DdaSteps)->Args({16, 0})->Args({64, 0})->Args({256, 0})->Args({64, 1});

struct ClusterScene {
  std::vector<Sphere> spheres;
  std::vector<Bounds> bounds;
  std::vector<std::uint32_t> cluster;
  std::vector<Ray> rays;  ///< camera rays over the scene
};

/// 64 clusters of pp random spheres (an npp scene of seed 001 L970) and 64x64 camera rays.
ClusterScene cluster_scene(int pp) {
  std::mt19937_64 rng(64 * pp);
  std::uniform_real_distribution<double> u(-1.0, 1.0), rad(0.2, 0.6);
  ClusterScene s;
  for (int c = 0; c < 64; ++c) {
    const Vec3 centre(10.0 * u(rng), 10.0 * u(rng), 10.0 * u(rng));
    for (int i = 0; i < pp; ++i) {
      const Sphere sp{centre + 1.5 * Vec3(u(rng), u(rng), u(rng)), rad(rng)};
      s.spheres.push_back(sp);
      s.bounds.push_back(Bounds{sp.c - Vec3(sp.r), sp.c + Vec3(sp.r)});
      s.cluster.push_back(static_cast<std::uint32_t>(c));
    }
  }
  const Vec3 eye(4.0, 6.0, 35.0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Vec3 target(-12.0 + 24.0 * (x + 0.5) / 64.0, -12.0 + 24.0 * (y + 0.5) / 64.0, 0.0);
      s.rays.push_back({eye, glm::normalize(target - eye)});
    }
  return s;
}

/// ShellTask + PrimTask closest hit, rays per second. Args: branching, pp, generic build.
void BM_ShellTreeClosest(benchmark::State& state) {
  const int b = static_cast<int>(state.range(0));
  const int pp = static_cast<int>(state.range(1));
  const ClusterScene s = cluster_scene(pp);
  const ShellTree tree = state.range(2) ? ShellTree::build(s.bounds, b, pp)
                                        : ShellTree::from_clusters(s.bounds, s.cluster, b);
  ShellTraverser trav(tree);
  ShellTraversalStats stats;
  std::size_t i = 0;
  for (auto _ : state) {
    const Ray& ray = s.rays[i++ % s.rays.size()];
    const ShellHit h = trav.closest_hit(
        ray, 1e-9, kInfinity,
        [&](std::uint32_t slot, double t0, double t1) {
          return rtsim::testing::sphere_root(s.spheres[slot].c, s.spheres[slot].r, ray, t0, t1);
        },
        stats);
    benchmark::DoNotOptimize(h);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  const double n = static_cast<double>(stats.rays);
  state.counters["box_tests/ray"] = static_cast<double>(stats.box_tests) / n;
  state.counters["prim_tests/ray"] = static_cast<double>(stats.prim_tests) / n;
  state.counters["tested/sorted"] = stats.mean_tested_fraction();
  state.SetLabel(state.range(2) ? "generic" : "clusters");
}
BENCHMARK(BM_ShellTreeClosest)
    ->Args({2, 8, 0})
    ->Args({4, 8, 0})
    ->Args({8, 8, 0})
    ->Args({4, 8, 1})
    ->Args({4, 20, 0});

void BM_ShellTreeBuild(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<Bounds> boxes = random_boxes(n, 3);
  for (auto _ : state) {
    ShellTree t = ShellTree::build(boxes, 4, 8);
    benchmark::DoNotOptimize(t.counts());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}
BENCHMARK(BM_ShellTreeBuild)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

/// The auxiliary processor's closest-hit search on the same scene, for comparison.
void BM_GridClosest(benchmark::State& state) {
  const ClusterScene s = cluster_scene(static_cast<int>(state.range(0)));
  Bounds scene;
  for (const Bounds& b : s.bounds) scene.extend(b);
  const UniformGrid grid(s.bounds, scene, choose_divisions(scene, s.bounds.size()));
  const Dda dda(grid);
  GridTraversalStats stats;
  std::size_t i = 0;
  for (auto _ : state) {
    const Ray& ray = s.rays[i++ % s.rays.size()];
    const GridHit h = grid_closest_hit(
        dda, ray, 1e-9, kInfinity,
        [&](std::uint32_t slot, double t0, double t1) {
          return rtsim::testing::sphere_root(s.spheres[slot].c, s.spheres[slot].r, ray, t0, t1);
        },
        stats);
    benchmark::DoNotOptimize(h);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  const double n = static_cast<double>(stats.rays);
  state.counters["steps/ray"] = static_cast<double>(stats.steps) / n;
  state.counters["prim_tests/ray"] = static_cast<double>(stats.prim_tests) / n;
}
BENCHMARK(BM_GridClosest)->Arg(8)->Arg(20);

}  // namespace
