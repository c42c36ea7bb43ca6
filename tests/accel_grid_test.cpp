// Ullner's uniform grid of subvolumes (seed 000 L592-L660): subvolume lists, the choice of
// divisions from his per-ray time model, memory for a million polygons, and the auxiliary
// processor's search against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "firmware/accel/grid_divisions.hpp"
#include "firmware/accel/grid_traversal.hpp"
#include "firmware/accel/uniform_grid.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::accel {
namespace {

struct Sphere {
  Vec3 c;
  double r;
};

TEST(AccelGrid, SubvolumeListsMatchBruteForceOverlap) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.0, 0.6);
  const Bounds scene = Bounds{Vec3(-4.0, -1.0, -2.0), Vec3(4.0, 3.0, 0.5)};
  const GridDivisions n{9, 5, 3};
  std::vector<Bounds> prims;
  for (int i = 0; i < 500; ++i) {
    const Vec3 c(4.5 * u(rng), 1.0 + 2.2 * u(rng), -0.75 + 1.5 * u(rng));
    const Vec3 h(size(rng), size(rng), size(rng));
    prims.push_back(Bounds{c - h, c + h});
  }
  const UniformGrid g(prims, scene, n);
  EXPECT_EQ(g.divisions(), n);
  EXPECT_EQ(g.cell_count(), 9u * 5u * 3u);
  std::size_t refs = 0, skipped = 0;
  for (const Bounds& p : prims) {
    const bool overlaps_scene = p.lo.x <= scene.hi.x && p.hi.x >= scene.lo.x &&
                                p.lo.y <= scene.hi.y && p.hi.y >= scene.lo.y &&
                                p.lo.z <= scene.hi.z && p.hi.z >= scene.lo.z;
    skipped += !overlaps_scene;
  }
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const Bounds cb = g.cell_bounds({x, y, z});
        std::vector<std::uint32_t> expect;
        for (std::uint32_t i = 0; i < prims.size(); ++i) {
          const Bounds& p = prims[i];
          if (p.lo.x <= cb.hi.x && p.hi.x >= cb.lo.x && p.lo.y <= cb.hi.y && p.hi.y >= cb.lo.y &&
              p.lo.z <= cb.hi.z && p.hi.z >= cb.lo.z)
            expect.push_back(i);
        }
        const auto got = g.cell({x, y, z});
        EXPECT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), expect);
        refs += expect.size();
      }
  EXPECT_EQ(g.reference_count(), refs);
  EXPECT_EQ(g.skipped_count(), skipped);
  std::printf("[ grid ] 500 boxes in 9x5x3: %zu references, %zu occupied subvolumes, %zu bytes\n",
              g.reference_count(), g.occupied_cell_count(), g.memory_bytes());
}

TEST(AccelGrid, BoundsOnAPlaneGoToBothSidesAndBadBoundsAreSkipped) {
  const Bounds scene = Bounds{Vec3(0.0), Vec3(4.0, 4.0, 4.0)};
  std::vector<Bounds> prims = {
      Bounds{Vec3(0.5, 0.5, 0.5), Vec3(1.0, 0.6, 0.6)},  // ends on the x = 1 plane
      Bounds{},                                          // empty
      Bounds{Vec3(std::nan(""), 0.0, 0.0), Vec3(1.0)},   // not finite
      Bounds{Vec3(10.0), Vec3(11.0)},                    // outside the scene
      Bounds{Vec3(-1.0), Vec3(0.2)},                     // partly outside: clipped
  };
  const UniformGrid g(prims, scene, {4, 4, 4});
  EXPECT_EQ(g.skipped_count(), 3u);
  EXPECT_EQ(g.cell({0, 0, 0}).size(), 2u);
  ASSERT_EQ(g.cell({1, 0, 0}).size(), 1u);
  EXPECT_EQ(g.cell({1, 0, 0})[0], 0u);
  EXPECT_TRUE(g.cell({2, 0, 0}).empty());
  // A flat scene (all in z = 0) still gets cells of positive width.
  const std::vector<Bounds> quad = {Bounds{Vec3(0.0), Vec3(1.0, 1.0, 0.0)}};
  const UniformGrid flat(quad, quad[0], {2, 2, 1});
  EXPECT_GT(flat.cell_size().z, 0.0);
  EXPECT_EQ(flat.cell({1, 1, 0}).size(), 1u);
  EXPECT_THROW(UniformGrid({}, scene, {0, 1, 1}), std::invalid_argument);
  EXPECT_THROW(UniformGrid({}, Bounds{}, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(UniformGrid({}, scene, {1 << 10, 1 << 10, 1 << 10}), std::length_error);
}

TEST(AccelGrid, UllnerModelGivesElevenDivisionsForAThousandPolygons) {
  // Seed 000 L654: minimum 14.3 us per ray at n_s = 11 for n_p = 1000 (Fig. 2-18).
  const UllnerGridModel m;
  int best = 1;
  for (int ns = 1; ns <= 40; ++ns)
    if (m.time_per_ray_us(ns, 1000.0) < m.time_per_ray_us(best, 1000.0)) best = ns;
  std::printf(
      "[ grid ] Ullner model: minimum %.2f us at n_s = %d (thesis: 14.3 us at 11); "
      "no subdivision %.1f us (thesis ~333 + latency); k = %.4f\n",
      m.time_per_ray_us(best, 1000.0), best, m.time_per_ray_us(1, 1000.0), m.density());
  EXPECT_EQ(best, 11);
  EXPECT_NEAR(m.time_per_ray_us(11, 1000.0), 14.3, 0.05);
  EXPECT_NEAR(m.density(), kUllnerGridDensity, 1e-6);
  // The automatic divisions reproduce it for a cube, and follow the box's aspect otherwise.
  const Bounds cube = Bounds{Vec3(0.0), Vec3(1.0)};
  EXPECT_EQ(choose_divisions(cube, 1000), (GridDivisions{11, 11, 11}));
  const GridDivisions slab = choose_divisions(Bounds{Vec3(0.0), Vec3(4.0, 2.0, 1.0)}, 1000);
  std::printf("[ grid ] 1000 polygons in a 4x2x1 box: %dx%dx%d\n", slab.x, slab.y, slab.z);
  EXPECT_NEAR(static_cast<double>(slab.x) / slab.z, 4.0, 0.6);
  EXPECT_NEAR(static_cast<double>(slab.y) / slab.z, 2.0, 0.4);
  EXPECT_NEAR(static_cast<double>(slab.cells()), std::pow(kUllnerGridDensity, 3) * 1000, 400.0);
  const GridDivisions flat = choose_divisions(Bounds{Vec3(0.0), Vec3(1.0, 1.0, 0.0)}, 1000);
  EXPECT_EQ(flat.z, 1);
  EXPECT_EQ(flat.x, 11);
  EXPECT_EQ(choose_divisions(cube, 0), (GridDivisions{1, 1, 1}));
  EXPECT_LE(choose_divisions(cube, 100000000, kUllnerGridDensity, 1000).cells(), 1000u);
}

TEST(AccelGrid, AMillionPolygonsFitInLittleMemory) {
  // The later machine must hold 1,000,000 polygons in < 2 GiB. Small random quads (bounds of
  // side up to 1/100 of the scene) with the automatic divisions.
  std::mt19937_64 rng(1000000);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Bounds> prims(1000000);
  for (Bounds& b : prims) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const Vec3 h(0.005 * u(rng), 0.005 * u(rng), 0.005 * u(rng));
    b = Bounds{c - h, c + h};
  }
  const Bounds scene = Bounds{Vec3(0.0), Vec3(1.0)};
  const GridDivisions n = choose_divisions(scene, prims.size());
  const auto start = std::chrono::steady_clock::now();
  const UniformGrid g(prims, scene, n);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double mib = g.memory_bytes() / 1048576.0;
  std::printf(
      "[ grid ] 1e6 polygons: %dx%dx%d, %zu references (%.2f per polygon), %.1f MiB "
      "(limit 2048 MiB), built in %.2f s\n",
      n.x, n.y, n.z, g.reference_count(), static_cast<double>(g.reference_count()) / prims.size(),
      mib, secs);
  EXPECT_LT(mib, 2048.0);
  EXPECT_EQ(g.skipped_count(), 0u);
  EXPECT_EQ(g.memory_bytes(), (g.cell_count() + 1 + g.reference_count()) * 4);
}

TEST(AccelGrid, AuxiliaryProcessorSearchFindsTheClosestHit) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0), rad(0.02, 0.3);
  std::normal_distribution<double> g01(0.0, 1.0);
  std::vector<Sphere> spheres;
  std::vector<Bounds> bounds;
  for (int i = 0; i < 400; ++i) {
    const Sphere s{Vec3(3.0 * u(rng), 2.0 * u(rng), 1.0 * u(rng)), rad(rng)};
    spheres.push_back(s);
    bounds.push_back(Bounds{s.c - Vec3(s.r), s.c + Vec3(s.r)});
  }
  Bounds scene;
  for (const Bounds& b : bounds) scene.extend(b);
  const UniformGrid grid(bounds, scene, choose_divisions(scene, bounds.size()));
  const Dda dda(grid);
  GridTraversalStats stats, shadow_stats;
  int hits = 0;
  const int rays = 3000;
  for (int r = 0; r < rays; ++r) {
    const Vec3 o(4.0 * u(rng), 3.0 * u(rng), 2.0 * u(rng));
    const Ray ray{o, glm::normalize(Vec3(g01(rng), g01(rng), g01(rng)))};
    const double t_max = r % 3 == 0 ? 2.0 : kInfinity;
    double brute_t = kInfinity;
    int brute_id = -1;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      const double t = rtsim::testing::sphere_root(spheres[i].c, spheres[i].r, ray, 1e-9,
                                                   std::min(brute_t, t_max));
      if (t < brute_t) {
        brute_t = t;
        brute_id = static_cast<int>(i);
      }
    }
    auto test = [&](std::uint32_t slot, double t0, double t1) {
      return rtsim::testing::sphere_root(spheres[slot].c, spheres[slot].r, ray, t0, t1);
    };
    const GridHit h = grid_closest_hit(dda, ray, 1e-9, t_max, test, stats);
    EXPECT_EQ(h.prim, brute_id);
    if (brute_id >= 0) {
      EXPECT_EQ(h.t, brute_t);
      ++hits;
    }
    const GridHit any = grid_any_hit(dda, ray, 1e-9, t_max, test, shadow_stats);
    EXPECT_EQ(any.valid(), brute_id >= 0);
  }
  std::printf(
      "[ grid ] closest hit: %d rays, %d hits, %.2f subvolumes, %.2f steps, "
      "%.2f polygon tests per ray (brute force: %zu); shadow: %.2f tests per ray\n",
      rays, hits, double(stats.cells_visited) / rays, double(stats.steps) / rays,
      double(stats.prim_tests) / rays, spheres.size(), double(shadow_stats.prim_tests) / rays);
  EXPECT_LT(stats.prim_tests, spheres.size() * rays / 10);
}

}  // namespace
}  // namespace rtsim::accel
