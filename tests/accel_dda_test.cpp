// Ullner's Appendix B DDA (seed 000 L2112-L2171) against a brute-force reference.
//
// Reference: for every subvolume, the t-interval in which the ray is inside it is the
// intersection of the per-axis slab intervals (t_min, t_max included). A subvolume the ray runs
// more than kEps through MUST be visited; one it does not reach within kEps must NOT be; the
// ones in between (the ray touches an edge or corner, or rounding decides) MAY be visited.
// kEps = 1e-9 of the scene scale: far above double rounding (1e-16 relative) and far below any
// cell width used here (>= 0.04).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "firmware/accel/dda.hpp"
#include "firmware/accel/grid_traversal.hpp"
#include "firmware/accel/uniform_grid.hpp"

namespace rtsim::accel {
namespace {

constexpr double kEpsRelative = 1e-9;

enum class Need { Must, May, MustNot };

struct Reference {
  std::vector<Need> need;  // per linear cell index
  std::vector<double> t0, t1;
  int must_count = 0;
  int may_count = 0;
};

Reference brute_force(const UniformGrid& g, const Ray& ray, double t_min, double t_max,
                      double eps) {
  const GridDivisions n = g.divisions();
  Reference ref;
  ref.need.assign(g.cell_count(), Need::MustNot);
  ref.t0.assign(g.cell_count(), 0.0);
  ref.t1.assign(g.cell_count(), 0.0);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const CellIndex c{x, y, z};
        const Bounds cb = g.cell_bounds(c);
        double lo = t_min, hi = t_max;
        bool possible = true;
        for (int k = 0; k < 3 && possible; ++k) {
          const double d = ray.direction[k], o = ray.origin[k];
          if (d == 0.0) {
            // Same rule as the corrected DDA: a ray in a plane goes to the cell above.
            const Bounds& box = g.box();
            if (!(o >= box.lo[k] && o <= box.hi[k])) {
              possible = false;
              break;
            }
            const double f = (o - box.lo[k]) / (box.hi[k] - box.lo[k]) * n[k];
            const int i = static_cast<int>(std::clamp(std::floor(f), 0.0, n[k] - 1.0));
            possible = i == c[k];
            continue;
          }
          double a = (cb.lo[k] - o) / d, b = (cb.hi[k] - o) / d;
          if (a > b) std::swap(a, b);
          lo = std::max(lo, a);
          hi = std::min(hi, b);
        }
        if (!possible) continue;
        const std::size_t li = g.linear_index(c);
        ref.t0[li] = lo;
        ref.t1[li] = hi;
        if (hi - lo > eps) {
          ref.need[li] = Need::Must;
          ++ref.must_count;
        } else if (hi - lo > -eps) {
          ref.need[li] = Need::May;
          ++ref.may_count;
        }
      }
  return ref;
}

struct Visited {
  std::vector<CellIndex> cells;
  std::vector<double> t0, t1;
  DdaResult result;
};

Visited run(const Dda& dda, const Ray& ray, double t_min, double t_max) {
  Visited v;
  const UniformGrid& g = dda.grid();
  v.result =
      dda.traverse(ray, t_min, t_max,
                   [&](const CellIndex& c, std::span<const std::uint32_t> s, double a, double b) {
                     // The span handed over is the grid's own list for that cell.
                     EXPECT_EQ(s.data(), g.cell(c).data());
                     v.cells.push_back(c);
                     v.t0.push_back(a);
                     v.t1.push_back(b);
                     return false;
                   });
  return v;
}

/// True if the visited cells are exactly right: every Must cell, no MustNot cell, no repeats.
bool matches(const UniformGrid& g, const Reference& ref, const Visited& v) {
  std::vector<char> seen(g.cell_count(), 0);
  int must_seen = 0;
  for (const CellIndex& c : v.cells) {
    const std::size_t li = g.linear_index(c);
    if (seen[li]) return false;
    seen[li] = 1;
    if (ref.need[li] == Need::MustNot) return false;
    if (ref.need[li] == Need::Must) ++must_seen;
  }
  return must_seen == ref.must_count;
}

struct Scenario {
  Bounds box;
  GridDivisions n;
};

Scenario random_grid(std::mt19937_64& rng, int max_div = 12) {
  std::uniform_real_distribution<double> pos(-5.0, 5.0), ext(0.5, 10.0);
  std::uniform_int_distribution<int> div(1, max_div);
  Scenario s;
  s.box.lo = Vec3(pos(rng), pos(rng), pos(rng));
  s.box.hi = s.box.lo + Vec3(ext(rng), ext(rng), ext(rng));
  s.n = {div(rng), div(rng), div(rng)};
  return s;
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    Vec3 v(g(rng), g(rng), g(rng));
    const double l = glm::length(v);
    if (l > 1e-6) return v / l;
  }
}

Vec3 random_point(std::mt19937_64& rng, const Bounds& b, double grow) {
  const Vec3 c = b.center(), e = b.extent() * (0.5 * grow);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return c + Vec3(u(rng) * e.x, u(rng) * e.y, u(rng) * e.z);
}

/// A grid plane coordinate exactly as the grid computes it.
double plane(const UniformGrid& g, int axis, int i) {
  if (i >= g.divisions()[axis]) return g.box().hi[axis];
  return g.cell_size()[axis] * i + g.box().lo[axis];
}

struct Tally {
  int rays = 0;
  int mismatches = 0;
  int with_may_cells = 0;
  int may_cells_visited = 0;  // touch-only cells the DDA did visit (allowed)
  int hits = 0;
};

/// Checks the corrected DDA on one ray in detail; returns whether it matched.
void check_corrected(const UniformGrid& g, const Ray& ray, double t_min, double t_max, Tally& tally,
                     const char* what) {
  const double scale = std::max(
      {1.0, max_abs_component(g.box().extent()), max_abs_component(ray.origin - g.box().center())});
  const double eps = kEpsRelative * scale;
  const Reference ref = brute_force(g, ray, t_min, t_max, eps);
  const Visited v = run(Dda(g, DdaVariant::Corrected), ray, t_min, t_max);
  ++tally.rays;
  tally.hits += v.result.entered;
  tally.with_may_cells += ref.may_count > 0;
  const bool ok = matches(g, ref, v);
  if (!ok) ++tally.mismatches;
  EXPECT_TRUE(ok) << what << ": origin " << ray.origin.x << "," << ray.origin.y << ","
                  << ray.origin.z << " dir " << ray.direction.x << "," << ray.direction.y << ","
                  << ray.direction.z << " visited " << v.cells.size() << " must " << ref.must_count
                  << " may " << ref.may_count;
  // Steps = visited - 1; t in order; each cell's interval agrees with the reference.
  EXPECT_EQ(v.result.steps + (v.result.entered ? 1 : 0), v.result.cells_visited);
  EXPECT_EQ(v.result.cells_visited, v.cells.size());
  EXPECT_FALSE(v.result.stalled || v.result.step_bound_reached || v.result.division_by_zero);
  for (std::size_t i = 0; i < v.cells.size(); ++i) {
    tally.may_cells_visited += ref.need[g.linear_index(v.cells[i])] == Need::May;
    EXPECT_LE(v.t0[i], v.t1[i]);
    if (i > 0) {
      EXPECT_EQ(v.t0[i], v.t1[i - 1]);
    }
    const std::size_t li = g.linear_index(v.cells[i]);
    if (ref.need[li] == Need::Must) {
      EXPECT_NEAR(v.t0[i], ref.t0[li], eps);
      EXPECT_NEAR(v.t1[i], ref.t1[li], eps);
    }
  }
}

TEST(AccelDda, CorrectedMatchesBruteForceOnRandomRays) {
  std::mt19937_64 rng(20250101);
  Tally tally;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int grid_no = 0; grid_no < 100; ++grid_no) {
    const Scenario s = random_grid(rng);
    const UniformGrid g({}, s.box, s.n);
    for (int r = 0; r < 100; ++r) {
      Ray ray{random_point(rng, g.box(), 2.5), random_unit(rng)};
      // Half of the rays are aimed at a random point of the grid, so most of those cross it.
      if (r % 2 == 1) ray.direction = glm::normalize(random_point(rng, g.box(), 1.0) - ray.origin);
      // Mostly unbounded rays; every fourth one is a segment ending somewhere in the box.
      const double t_max =
          r % 4 == 3 ? u01(rng) * 2.0 * max_abs_component(g.box().extent()) : kInfinity;
      check_corrected(g, ray, 0.0, t_max, tally, "random");
    }
  }
  std::printf(
      "[ dda ] corrected, random rays: %d rays, %d entered the grid, %d mismatches, "
      "%d with touch-only cells\n",
      tally.rays, tally.hits, tally.mismatches, tally.with_may_cells);
  EXPECT_EQ(tally.mismatches, 0);
  EXPECT_GT(tally.hits, tally.rays / 4);
}

TEST(AccelDda, CorrectedHandlesAxisParallelAndPlaneRays) {
  std::mt19937_64 rng(7);
  Tally tally;
  for (int grid_no = 0; grid_no < 40; ++grid_no) {
    const Scenario s = random_grid(rng);
    const UniformGrid g({}, s.box, s.n);
    std::uniform_int_distribution<int> pick(0, 3);
    for (int axis = 0; axis < 3; ++axis) {
      for (int sign = -1; sign <= 1; sign += 2) {
        for (int r = 0; r < 12; ++r) {
          Vec3 dir(0.0);
          dir[axis] = sign;
          Vec3 o = random_point(rng, g.box(), 1.6);
          // Snap the two other coordinates to grid planes (0: free, 1: interior plane,
          // 2: min face, 3: max face), so some rays lie exactly in one or two planes.
          for (int other = 0; other < 3; ++other) {
            if (other == axis) continue;
            const int n = g.divisions()[other];
            switch (pick(rng)) {
              case 1:
                o[other] = plane(g, other, std::uniform_int_distribution<int>(0, n)(rng));
                break;
              case 2:
                o[other] = g.box().lo[other];
                break;
              case 3:
                o[other] = g.box().hi[other];
                break;
              default:
                break;
            }
          }
          check_corrected(g, Ray{o, dir}, 0.0, kInfinity, tally, "axis-parallel");
        }
      }
    }
    // Rays parallel to a coordinate plane but oblique in it (one zero component).
    for (int r = 0; r < 30; ++r) {
      Vec3 dir = random_unit(rng);
      dir[r % 3] = 0.0;
      dir = glm::normalize(dir);
      Vec3 o = random_point(rng, g.box(), 1.6);
      if (r % 2 == 0) o[r % 3] = plane(g, r % 3, r % (g.divisions()[r % 3] + 1));
      check_corrected(g, Ray{o, dir}, 0.0, kInfinity, tally, "plane-parallel");
    }
  }
  std::printf("[ dda ] corrected, axis/plane-parallel rays: %d rays, %d entered, %d mismatches\n",
              tally.rays, tally.hits, tally.mismatches);
  EXPECT_EQ(tally.mismatches, 0);
}

TEST(AccelDda, CorrectedHandlesEntryOnFacesEdgesCorners) {
  std::mt19937_64 rng(99);
  Tally tally;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int grid_no = 0; grid_no < 40; ++grid_no) {
    const Scenario s = random_grid(rng);
    const UniformGrid g({}, s.box, s.n);
    const GridDivisions n = g.divisions();
    for (int r = 0; r < 40; ++r) {
      // A point on the box surface at a grid vertex (corner of subvolumes), on a grid edge, or
      // on a face; then either start there (t = 0 exactly on it) or aim at it from outside.
      Vec3 p;
      const int kind = r % 3;  // 0: vertex, 1: edge, 2: face
      for (int k = 0; k < 3; ++k) {
        const int i = std::uniform_int_distribution<int>(0, n[k])(rng);
        p[k] = (k < 3 - kind) ? plane(g, k, i) : g.box().lo[k] + u01(rng) * g.box().extent()[k];
      }
      const int face_axis = r % 3;
      p[face_axis] = (r / 3) % 2 ? g.box().hi[face_axis] : g.box().lo[face_axis];
      Vec3 dir = random_unit(rng);
      // Point inward across that face.
      const double inward = (r / 3) % 2 ? -1.0 : 1.0;
      dir[face_axis] = inward * std::fabs(dir[face_axis]) + inward * 0.05;
      dir = glm::normalize(dir);
      if (r % 2 == 0) {
        check_corrected(g, Ray{p, dir}, 0.0, kInfinity, tally, "start on surface");
      } else {
        const double back = 1.0 + 3.0 * u01(rng);
        check_corrected(g, Ray{p - back * dir, dir}, 0.0, kInfinity, tally, "enter at point");
      }
      // Leaving through the same point (pointing outward): touch-only or nothing.
      check_corrected(g, Ray{p, -dir}, 0.0, kInfinity, tally, "leave from surface");
    }
  }
  std::printf(
      "[ dda ] corrected, entries on faces/edges/corners: %d rays, %d entered, "
      "%d mismatches, %d with touch-only cells, %d touch-only cells visited\n",
      tally.rays, tally.hits, tally.mismatches, tally.with_may_cells, tally.may_cells_visited);
  EXPECT_EQ(tally.mismatches, 0);
}

TEST(AccelDda, CorrectedMissesAndInsideStarts) {
  const UniformGrid g({}, Bounds{Vec3(0.0), Vec3(4.0, 2.0, 1.0)}, {4, 3, 2});
  const Dda dda(g);
  auto count = [&](const Ray& r, double t_min = 0.0, double t_max = kInfinity) {
    return run(dda, r, t_min, t_max).result.cells_visited;
  };
  // Pointing away, passing beside, grazing along an outer face line, behind the origin.
  EXPECT_EQ(count({Vec3(-1.0, 1.0, 0.5), glm::normalize(Vec3(-1.0, 0.2, 0.0))}), 0u);
  EXPECT_EQ(count({Vec3(-1.0, 3.0, 0.5), Vec3(1.0, 0.0, 0.0)}), 0u);
  EXPECT_EQ(count({Vec3(5.0, 1.0, 0.5), Vec3(1.0, 0.0, 0.0)}), 0u);
  // A segment that ends before the box.
  EXPECT_EQ(count({Vec3(-1.0, 1.0, 0.5), Vec3(1.0, 0.0, 0.0)}, 0.0, 0.5), 0u);
  // A ray touching the box only along an outer edge (x from -1 on the line y=2, z=1): it runs
  // inside the closed box but in no subvolume's interior; by the plane rule it belongs to the
  // last cell in y and z.
  EXPECT_EQ(count({Vec3(-1.0, 2.0, 1.0), Vec3(1.0, 0.0, 0.0)}), 4u);
  // Touching a corner only (zero length): miss.
  EXPECT_EQ(count({Vec3(-1.0, 1.0, 0.5), glm::normalize(Vec3(1.0, -1.0, 0.0))}), 0u);
  // Starting inside: visits the origin's cell first.
  Visited v = run(dda, {Vec3(2.5, 0.5, 0.25), Vec3(1.0, 0.0, 0.0)}, 0.0, kInfinity);
  ASSERT_EQ(v.cells.size(), 2u);
  EXPECT_EQ(v.cells[0], (CellIndex{2, 0, 0}));
  EXPECT_EQ(v.t0[0], 0.0);
  // NaN / degenerate input never produces a walk.
  EXPECT_EQ(count({Vec3(std::nan(""), 0.0, 0.0), Vec3(1.0, 0.0, 0.0)}), 0u);
  EXPECT_EQ(count({Vec3(1.0, 1.0, 0.5), Vec3(1.0, 0.0, 0.0)}, std::nan(""), kInfinity), 0u);
}

TEST(AccelDda, ExactDiagonalTiesStepDiagonally) {
  // Box [0,8]^3, 8 cells per axis, so planes are integers. A ray in the plane z = 0.5 along
  // x = y passes exactly through the grid edges at integer (x, y): tx == ty at every crossing.
  const UniformGrid g({}, Bounds{Vec3(0.0), Vec3(8.0)}, {8, 8, 8});
  const Dda dda(g);
  const Vec3 d = glm::normalize(Vec3(1.0, 1.0, 0.0));
  Visited v = run(dda, {Vec3(-1.0, -1.0, 0.5), d}, 0.0, kInfinity);
  ASSERT_EQ(v.cells.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(v.cells[i], (CellIndex{i, i, 0}));
  EXPECT_EQ(v.result.steps, 7u);
  // Through the main diagonal corner to corner: ties of all three axes.
  v = run(dda, {Vec3(-2.0), glm::normalize(Vec3(1.0))}, 0.0, kInfinity);
  ASSERT_EQ(v.cells.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(v.cells[i], (CellIndex{i, i, i}));
  // The printed program reports the corner entry as a miss (i = ceil(0) = 0, note 000 §4.6
  // issue 2) ...
  Visited p =
      run(Dda(g, DdaVariant::AsPrinted), {Vec3(-2.0), glm::normalize(Vec3(1.0))}, 0.0, kInfinity);
  EXPECT_FALSE(p.result.entered);
  // ... and from inside, where tx = ty = tz, it stalls on the first tie (stopped, not hung).
  const Ray inside{Vec3(0.5), glm::normalize(Vec3(1.0))};
  p = run(Dda(g, DdaVariant::AsPrinted), inside, 0.0, kInfinity);
  EXPECT_TRUE(p.result.stalled);
  EXPECT_EQ(p.result.cells_visited, 1u);
  v = run(dda, inside, 0.0, kInfinity);
  ASSERT_EQ(v.cells.size(), 8u);
  EXPECT_EQ(v.cells[7], (CellIndex{7, 7, 7}));
}

TEST(AccelDda, AsPrintedMismatchesAndNeverHangs) {
  // Ullner's own setting: an 8x8x8 grid, random rays (seed note 000 §4.6 reports 150 of 200).
  std::mt19937_64 rng(1983);
  struct PrintedTally {
    int rays = 0, crossing = 0, mismatches = 0, crossing_mismatches = 0;
    int reported_miss = 0, stalled = 0, wrong_cells = 0;  // why crossing rays went wrong
  };
  // Rays from random points in 2.5x the box, random directions; only_crossing: draw until the
  // ray really crosses the grid.
  auto measure = [&](const UniformGrid& g, int rays, bool only_crossing, PrintedTally& t) {
    const double eps = kEpsRelative * std::max(1.0, max_abs_component(g.box().extent()));
    while (t.rays < rays) {
      const Ray ray{random_point(rng, g.box(), 2.5), random_unit(rng)};
      const Reference ref = brute_force(g, ray, 0.0, kInfinity, eps);
      const bool crossing = ref.must_count > 0;
      if (only_crossing && !crossing) continue;
      const Visited v = run(Dda(g, DdaVariant::AsPrinted), ray, 0.0, kInfinity);
      ++t.rays;
      t.crossing += crossing;
      const bool ok = matches(g, ref, v);
      t.mismatches += !ok;
      if (crossing && !ok) {
        ++t.crossing_mismatches;
        if (v.result.stalled) {
          ++t.stalled;
        } else if (!v.result.entered) {
          ++t.reported_miss;
        } else {
          ++t.wrong_cells;
        }
      }
      // It never runs away: at most n_x + n_y + n_z + 3 steps, and never a division by zero
      // for these (all-non-zero) directions.
      EXPECT_LE(v.result.steps, Dda(g).step_bound());
      EXPECT_FALSE(v.result.division_by_zero);
    }
  };
  auto pct = [](int a, int b) { return b ? 100.0 * a / b : 0.0; };
  const UniformGrid cube({}, Bounds{Vec3(0.0), Vec3(1.0)}, {8, 8, 8});
  PrintedTally all, crossing, random_grids;
  measure(cube, 2000, false, all);
  measure(cube, 2000, true, crossing);
  for (int grid_no = 0; grid_no < 50; ++grid_no) {
    const Scenario s = random_grid(rng);
    PrintedTally t;
    measure(UniformGrid({}, s.box, s.n), 40, true, t);
    random_grids.rays += t.rays;
    random_grids.crossing_mismatches += t.crossing_mismatches;
  }
  int division_by_zero = 0;
  for (int r = 0; r < 600; ++r) {
    Vec3 dir(0.0);
    dir[r % 3] = (r / 3) % 2 ? 1.0 : -1.0;
    const Ray ray{random_point(rng, cube.box(), 1.5), dir};
    division_by_zero +=
        run(Dda(cube, DdaVariant::AsPrinted), ray, 0.0, kInfinity).result.division_by_zero;
  }
  std::printf(
      "[ dda ] as-printed, 8x8x8, random rays: %d/%d mismatch (%.1f%%); of the %d that "
      "cross the grid %d (%.1f%%)\n",
      all.mismatches, all.rays, pct(all.mismatches, all.rays), all.crossing,
      all.crossing_mismatches, pct(all.crossing_mismatches, all.crossing));
  std::printf(
      "[ dda ] as-printed, 8x8x8, rays that cross the grid: %d/%d mismatch (%.1f%%; "
      "note 000 §4.6: 150/200 = 75%%): %d wrong cells, %d reported as misses, %d "
      "stalled on a tie\n",
      crossing.crossing_mismatches, crossing.rays, pct(crossing.crossing_mismatches, crossing.rays),
      crossing.wrong_cells, crossing.reported_miss, crossing.stalled);
  std::printf(
      "[ dda ] as-printed, 50 random non-cubic grids, crossing rays: %d/%d mismatch "
      "(%.1f%%)\n",
      random_grids.crossing_mismatches, random_grids.rays,
      pct(random_grids.crossing_mismatches, random_grids.rays));
  std::printf("[ dda ] as-printed, axis-parallel rays: %d/600 stopped for division by zero\n",
              division_by_zero);
  // The printed initialisation is wrong for every a > 0 axis, so most rays that cross more
  // than one subvolume go wrong. Require a clearly measurable fraction (note: 75%).
  EXPECT_GT(pct(crossing.crossing_mismatches, crossing.rays), 50.0);
  EXPECT_GT(pct(random_grids.crossing_mismatches, random_grids.rays), 30.0);
  EXPECT_EQ(division_by_zero, 600);
}

TEST(AccelDda, VisitorCanStopAndStepsCount) {
  const UniformGrid g({}, Bounds{Vec3(0.0), Vec3(10.0, 5.0, 3.0)}, {10, 5, 3});
  const Dda dda(g);
  const Ray ray{Vec3(-1.0, 0.3, 0.2), glm::normalize(Vec3(1.0, 0.37, 0.21))};
  const Visited all = run(dda, ray, 0.0, kInfinity);
  ASSERT_GT(all.cells.size(), 5u);
  int calls = 0;
  const DdaResult r = dda.traverse(
      ray, 0.0, kInfinity, [&](const CellIndex&, auto, double, double) { return ++calls == 3; });
  EXPECT_TRUE(r.stopped_by_visitor);
  EXPECT_EQ(r.cells_visited, 3u);
  EXPECT_EQ(r.steps, 2u);
  // A void visitor walks everything.
  const DdaResult w =
      dda.traverse(ray, 0.0, kInfinity, [](const CellIndex&, auto, double, double) {});
  EXPECT_EQ(w.cells_visited, all.cells.size());
  EXPECT_EQ(w.steps, all.cells.size() - 1);
}

// A walk gone on from any place it reached (traverse_from: ullner-array's processors hand a ray
// on with the place their walk stopped) visits the same cells with the same t's from there, and
// its result counts the whole walk, on both variants; axis-parallel rays and segments included.
TEST(AccelDda, AWalkGoneOnFromAPlaceItReachedIsTheSameWalk) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int places = 0;
  for (int grid_no = 0; grid_no < 40; ++grid_no) {
    const Scenario s = random_grid(rng, 16);
    const UniformGrid g({}, s.box, s.n);
    for (const DdaVariant variant : {DdaVariant::Corrected, DdaVariant::AsPrinted}) {
      const Dda dda(g, variant);
      for (int r = 0; r < 40; ++r) {
        Ray ray{random_point(rng, g.box(), 2.5), random_unit(rng)};
        if (r % 2 == 1)
          ray.direction = glm::normalize(random_point(rng, g.box(), 1.0) - ray.origin);
        if (r % 5 == 4) ray.direction[r % 3] = 0.0;  // axis-parallel in one axis
        if (r % 5 == 4 && glm::length(ray.direction) == 0.0) continue;
        const double t_max =
            r % 4 == 3 ? u01(rng) * 2.0 * max_abs_component(g.box().extent()) : kInfinity;
        const Visited all = run(dda, ray, 0.0, t_max);
        for (std::size_t k = 0; k < all.cells.size(); ++k) {
          const DdaPlace at{.cell = all.cells[k], .t_enter = all.t0[k], .visited = k + 1};
          Visited rest;
          rest.result = dda.traverse_from(ray, 0.0, t_max, at,
                                          [&](const CellIndex& c, auto, double t0, double t1) {
                                            rest.cells.push_back(c);
                                            rest.t0.push_back(t0);
                                            rest.t1.push_back(t1);
                                          });
          ASSERT_EQ(rest.cells.size(), all.cells.size() - k) << "grid " << grid_no << " ray " << r;
          for (std::size_t j = 0; j < rest.cells.size(); ++j) {
            EXPECT_EQ(rest.cells[j], all.cells[k + j]);
            EXPECT_EQ(rest.t0[j], all.t0[k + j]);
            EXPECT_EQ(rest.t1[j], all.t1[k + j]);
          }
          EXPECT_EQ(rest.result.cells_visited, all.result.cells_visited);
          EXPECT_EQ(rest.result.steps, all.result.steps);
          EXPECT_EQ(rest.result.entered, all.result.entered);
          ++places;
        }
      }
    }
  }
  std::printf("[ dda ] walks gone on from %d places\n", places);
  EXPECT_GT(places, 1000);
}

}  // namespace
}  // namespace rtsim::accel
