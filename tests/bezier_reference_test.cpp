// The double-precision reference ray/Bezier-patch solver (firmware/kernels/bezier_reference.*):
// against analytic plane intersections on flat patches, against known points of the Newell
// teapot, and against a brute-force tessellation (so that "nearest root" is checked too).
#include "firmware/kernels/bezier_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "firmware/kernels/bezier_patch_math.hpp"
#include "tests/bezier_teapot.hpp"

namespace rtsim::kernels {
namespace {

/// A bilinear map written as a bicubic patch: control[4i + j] = bilinear(j/3, i/3) (degree
/// elevation of a bilinear map is exact), with u along j as scenes::BezierPatch says.
scenes::BezierPatch bilinear_patch(const Vec3& p00, const Vec3& p10, const Vec3& p01,
                                   const Vec3& p11) {
  scenes::BezierPatch patch;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double u = j / 3.0, v = i / 3.0;
      patch.control[static_cast<std::size_t>(4 * i + j)] =
          (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11;
    }
  return patch;
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    const double l = glm::length(v);
    if (l > 1e-3) return v / l;
  }
}

/// A direction within `max_angle` (radians) of `axis` (unit), uniformly in angle.
Vec3 tilted(const Vec3& axis, double max_angle, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> a(0.0, max_angle), phi(0.0, 2.0 * kPi);
  const Vec3 helper = std::fabs(axis.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 e1 = glm::normalize(glm::cross(axis, helper)), e2 = glm::cross(axis, e1);
  const double th = a(rng), ph = phi(rng);
  return glm::normalize(std::cos(th) * axis +
                        std::sin(th) * (std::cos(ph) * e1 + std::sin(ph) * e2));
}

// Tolerance 1e-12: the flat patch's intersection is a 3x3 linear solve; Newton lands on it to
// rounding (~1e-15 of the 2-unit scale), so 1e-12 leaves room for accumulated rounding only.
TEST(BezierReference, FlatParallelogramMatchesAnalyticPlaneIntersection) {
  const Vec3 a(0.3, -0.2, 1.0), eu(2.0, 0.4, -0.3), ev(-0.5, 1.5, 0.6);
  const auto patch = bilinear_patch(a, a + eu, a + ev, a + eu + ev);
  const auto kernel = BezierReferenceKernel::from(patch);
  const Vec3 n = glm::normalize(glm::cross(eu, ev));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> param(-0.4, 1.4);
  int hits = 0, misses = 0;
  for (int k = 0; k < 2000; ++k) {
    const double u0 = param(rng), v0 = param(rng);
    const Vec3 target = a + u0 * eu + v0 * ev;
    const Vec3 d = tilted(k % 2 ? n : -n, 1.2, rng);  // up to ~69 degrees off the normal
    const double t0 = 3.0;
    const Ray ray{target - t0 * d, d};
    // analytic: t = (a - O).n / (D.n); (u, v) by construction
    const double t_plane = glm::dot(a - ray.origin, n) / glm::dot(d, n);
    SurfaceHit hit;
    const bool inside = u0 >= 0 && u0 <= 1 && v0 >= 0 && v0 <= 1;
    const bool near_edge = std::fabs(u0) < 1e-6 || std::fabs(u0 - 1) < 1e-6 ||
                           std::fabs(v0) < 1e-6 || std::fabs(v0 - 1) < 1e-6;
    if (near_edge) continue;
    const bool got = kernel.intersect(ray, 0.0, kInfinity, hit);
    ASSERT_EQ(got, inside) << "u0=" << u0 << " v0=" << v0;
    if (!got) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(hit.t, t_plane, 1e-12);
    EXPECT_NEAR(hit.u, u0, 1e-12);
    EXPECT_NEAR(hit.v, v0, 1e-12);
    EXPECT_NEAR(std::fabs(glm::dot(hit.geometric_normal, n)), 1.0, 1e-12);
  }
  std::printf("flat parallelogram: %d hits, %d misses, all at the analytic t, u, v (1e-12)\n", hits,
              misses);
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 500);
}

// A planar trapezoid (bilinear, not a parallelogram): t must be the plane's t and the returned
// (u, v) must map to the hit point.
TEST(BezierReference, FlatTrapezoidMatchesPlaneAndReproducesPoint) {
  const Vec3 p00(0, 0, 0), p10(3, 0, 0), p01(0.5, 1, 0), p11(2, 1, 0);  // in z = 0
  const auto patch = bilinear_patch(p00, p10, p01, p11);
  const auto kernel = BezierReferenceKernel::from(patch);
  const ControlNet<double> net = control_net_from(patch);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> param(0.001, 0.999);
  for (int k = 0; k < 1000; ++k) {
    const double u0 = param(rng), v0 = param(rng);
    const Vec3 target = evaluate(net, u0, v0);
    const Vec3 d = tilted(Vec3(0, 0, k % 2 ? 1.0 : -1.0), 1.2, rng);
    const Ray ray{target - 2.5 * d, d};
    const double t_plane = -ray.origin.z / d.z;
    SurfaceHit hit;
    ASSERT_TRUE(kernel.intersect(ray, 0.0, kInfinity, hit));
    EXPECT_NEAR(hit.t, t_plane, 1e-12);
    EXPECT_NEAR(hit.u, u0, 1e-12);
    EXPECT_NEAR(hit.v, v0, 1e-12);
    EXPECT_LT(glm::length(evaluate(net, hit.u, hit.v) - ray.at(hit.t)), 1e-12);
  }
  // a miss beside the trapezoid's slanted edge (u = 1.1 lies outside for every v)
  const Vec3 outside = evaluate(net, 1.1, 0.5);
  SurfaceHit hit;
  EXPECT_FALSE(kernel.intersect(Ray{outside + Vec3(0, 0, 1), Vec3(0, 0, -1)}, 0, kInfinity, hit));
}

TEST(BezierReference, RangeAndDirectionConventions) {
  const auto patch = bilinear_patch(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(-1, 1, 0), Vec3(1, 1, 0));
  const auto kernel = BezierReferenceKernel::from(patch);
  SurfaceHit hit;
  const Ray down{Vec3(0.2, 0.1, 4.0), Vec3(0, 0, -1)};
  ASSERT_TRUE(kernel.intersect(down, 0.0, kInfinity, hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-14);
  EXPECT_NEAR(hit.u, 0.6, 1e-14);
  EXPECT_NEAR(hit.v, 0.55, 1e-14);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0, 1e-14);  // Q_u x Q_v = +z, not flipped toward the ray
  EXPECT_FALSE(kernel.intersect(down, 0.0, 3.9, hit));
  EXPECT_FALSE(kernel.intersect(down, 4.1, kInfinity, hit));
  EXPECT_FALSE(kernel.intersect(Ray{down.origin, -down.direction}, 0.0, kInfinity, hit));
  // a non-unit direction: t is in its units
  ASSERT_TRUE(kernel.intersect(Ray{down.origin, Vec3(0, 0, -2)}, 0.0, kInfinity, hit));
  EXPECT_NEAR(hit.t, 2.0, 1e-14);
  // bad input never hits
  EXPECT_FALSE(kernel.intersect(Ray{down.origin, Vec3(0.0)}, 0.0, kInfinity, hit));
  EXPECT_FALSE(
      kernel.intersect(Ray{Vec3(std::nan(""), 0, 1), down.direction}, 0.0, kInfinity, hit));
  auto bad = patch;
  bad.control[5].y = std::nan("");
  EXPECT_FALSE(BezierReferenceKernel::from(bad).intersect(down, 0.0, kInfinity, hit));
}

/// Is (u, v) a regular point (the parameters are unique there)? Not at the collapsed edges of
/// the teapot's lid and bottom, where many (u, v) map to the same point.
bool regular(const ControlNet<double>& net, double u, double v) {
  Vec3 q, qu, qv;
  evaluate_with_derivatives(net, u, v, q, qu, qv);
  return glm::length(qu) > 1e-3 && glm::length(qv) > 1e-3;
}

// Rays aimed at known surface points from close by (origin 0.01 from the point, well inside
// the teapot's smallest radius of curvature, so nothing of the same patch lies in between). The
// reference must recover every point to 1e-9 (absolute; the teapot is ~8 units across, so
// ~1e-10 relative): Newton converges quadratically and the residual tolerance is 1e-11 of scale.
TEST(BezierReference, RecoversKnownTeapotPointsFromNearby) {
  const auto patches = bezier_test::teapot();
  ASSERT_EQ(patches.size(), 32u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  int checked = 0;
  double worst_point = 0.0, worst_t = 0.0, worst_param = 0.0;
  ReferenceCounters counters;
  for (const auto& patch : patches) {
    const ControlNet<double> net = control_net_from(patch);
    for (int k = 0; k < 60; ++k) {
      // grid corners and edges too (k < 9), then random interior points
      const double u0 = k < 9 ? (k % 3) * 0.5 : param(rng);
      const double v0 = k < 9 ? (k / 3) * 0.5 : param(rng);
      const Vec3 target = evaluate(net, u0, v0);
      Vec3 n;
      ASSERT_TRUE(patch_normal(net, u0, v0, n));
      const Vec3 d = tilted(k % 2 ? n : -n, 0.8, rng);  // up to ~46 degrees off the normal
      const double t0 = 0.01;
      const Ray ray{target - t0 * d, d};
      SurfaceHit hit;
      ASSERT_TRUE(reference_intersect(net, ray, 0.0, kInfinity, hit, &counters))
          << "u0=" << u0 << " v0=" << v0;
      const double point_error = glm::length(ray.at(hit.t) - target);
      worst_point = std::max(worst_point, point_error);
      worst_t = std::max(worst_t, std::fabs(hit.t - t0));
      EXPECT_LT(point_error, 1e-9) << "u0=" << u0 << " v0=" << v0;
      EXPECT_NEAR(hit.t, t0, 1e-9);
      if (regular(net, u0, v0)) {
        worst_param = std::max(worst_param, std::max(std::fabs(hit.u - u0), std::fabs(hit.v - v0)));
        EXPECT_NEAR(hit.u, u0, 1e-8);
        EXPECT_NEAR(hit.v, v0, 1e-8);
      }
      ++checked;
    }
  }
  std::printf(
      "teapot near rays: %d points; worst |point error| %.2e, |t error| %.2e, |param error| "
      "%.2e (tolerance 1e-9 / 1e-9 / 1e-8)\n",
      checked, worst_point, worst_t, worst_param);
  std::printf("  per call: %.1f box tests, %.2f Newton starts, %.1f Newton iterations\n",
              double(counters.box_tests) / counters.calls,
              double(counters.newton_starts) / counters.calls,
              double(counters.newton_iterations) / counters.calls);
}

/// Brute force for the nearest root: the patch tessellated into n x n bilinear cells, two
/// triangles each, Moller-Trumbore style (our own). Returns the nearest t and the |cos| between
/// the ray and the triangle there.
bool tessellated_nearest(const ControlNet<double>& net, const Ray& ray, int n, double& best_t,
                         double& best_cos) {
  std::vector<Vec3> grid(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      grid[static_cast<std::size_t>(a * (n + 1) + b)] = evaluate(net, double(a) / n, double(b) / n);
  best_t = kInfinity;
  auto tri = [&](const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, pv = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, pv);
    if (std::fabs(det) < 1e-300) return;
    const Vec3 tv = ray.origin - p0;
    const double u = glm::dot(tv, pv) / det;
    if (u < 0 || u > 1) return;
    const Vec3 qv = glm::cross(tv, e1);
    const double v = glm::dot(ray.direction, qv) / det;
    if (v < 0 || u + v > 1) return;
    const double t = glm::dot(e2, qv) / det;
    if (t > 0 && t < best_t) {
      best_t = t;
      const Vec3 nn = glm::cross(e1, e2);
      best_cos = std::fabs(glm::dot(nn, ray.direction)) / glm::length(nn);
    }
  };
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const auto& p00 = grid[static_cast<std::size_t>(a * (n + 1) + b)];
      const auto& p01 = grid[static_cast<std::size_t>(a * (n + 1) + b + 1)];
      const auto& p10 = grid[static_cast<std::size_t>((a + 1) * (n + 1) + b)];
      const auto& p11 = grid[static_cast<std::size_t>((a + 1) * (n + 1) + b + 1)];
      tri(p00, p10, p11);
      tri(p00, p11, p01);
    }
  return best_t < kInfinity;
}

// Rays through known surface points from far away (2x the teapot size, any direction): the
// nearest root may now be another part of the same patch. The reference must return either the
// known point (to 1e-9) or a nearer genuine root (|Q(u,v) - ray(t)| < 1e-9). Independently, a
// 96 x 96 tessellation must agree on the nearest hit wherever the crossing is not grazing
// (|cos| > 0.2 at the tessellated hit): same t within 0.01 (the tessellation's chord error is
// ~1e-3 here; 0.01 at |cos| = 0.2 allows for it).
TEST(BezierReference, FindsNearestRootOnTeapotPatches) {
  const auto patches = bezier_test::teapot();
  const double size = glm::length(bezier_test::patches_bounds(patches).extent());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  int recovered = 0, nearer = 0, tess_checked = 0, tess_disagree = 0;
  for (const auto& patch : patches) {
    const ControlNet<double> net = control_net_from(patch);
    for (int k = 0; k < 12; ++k) {
      const double u0 = param(rng), v0 = param(rng);
      const Vec3 target = evaluate(net, u0, v0);
      const Vec3 d = random_unit(rng);
      const double t0 = 2.0 * size;
      const Ray ray{target - t0 * d, d};
      SurfaceHit hit;
      ASSERT_TRUE(reference_intersect(net, ray, 0.0, kInfinity, hit));
      ASSERT_LT(hit.t, t0 + 1e-9);
      if (std::fabs(hit.t - t0) < 1e-9) {
        EXPECT_LT(glm::length(ray.at(hit.t) - target), 1e-9);
        ++recovered;
      } else {
        EXPECT_LT(glm::length(evaluate(net, hit.u, hit.v) - ray.at(hit.t)), 1e-9);
        ++nearer;
      }
      double tess_t = 0, tess_cos = 0;
      if (tessellated_nearest(net, ray, 96, tess_t, tess_cos) && tess_cos > 0.2) {
        ++tess_checked;
        if (std::fabs(tess_t - hit.t) > 0.01) {
          ++tess_disagree;
          ADD_FAILURE() << "tessellation t " << tess_t << " vs reference " << hit.t;
        }
      }
    }
  }
  std::printf(
      "teapot far rays: %d recovered the aimed-at point, %d found a nearer genuine root; "
      "tessellation agrees on %d/%d non-grazing rays\n",
      recovered, nearer, tess_checked - tess_disagree, tess_checked);
  EXPECT_GT(recovered, 200);
}

}  // namespace
}  // namespace rtsim::kernels
