// Triangle kernel against an independent reference: plane intersection and area barycentrics in
// long double (a different formulation from the kernel's ray-space edge functions).
#include <gtest/gtest.h>

#include <cstdio>

#include "firmware/kernels/triangle.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::kernels {
namespace {

using testing::hit_is_sane;
using testing::RandomGeometry;

using LV = glm::vec<3, long double, glm::defaultp>;

struct Reference {
  bool valid = false;  // the ray is not (nearly) parallel to the plane
  bool hit = false;
  long double t = 0, u = 0, v = 0;
  long double margin = 0;  // smallest barycentric (negative outside), scaled to distance
  LV normal{0};
};

Reference reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray, double t_min,
                    double t_max, long double grazing) {
  Reference r;
  const LV a(p0), b(p1), c(p2), o(ray.origin), d(ray.direction);
  const LV e1 = b - a, e2 = c - a;
  const LV n = glm::cross(e1, e2);
  const long double nn = glm::dot(n, n);
  const long double denom = glm::dot(n, d);
  if (std::fabs(denom) <= grazing * std::sqrt(nn)) return r;  // grazing: no clear reference
  r.valid = true;
  r.t = glm::dot(n, a - o) / denom;
  const LV p = o + r.t * d;
  r.u = glm::dot(n, glm::cross(p - a, e2)) / nn;
  r.v = glm::dot(n, glm::cross(e1, p - a)) / nn;
  const long double w = 1.0L - r.u - r.v;
  const long double size = std::sqrt(std::fmax(glm::dot(e1, e1), glm::dot(e2, e2)));
  r.margin = std::fmin(w, std::fmin(r.u, r.v)) * size;
  r.hit = r.u >= 0 && r.v >= 0 && w >= 0 && r.t > t_min && r.t < t_max;
  r.normal = n / std::sqrt(nn);
  return r;
}

TEST(TriangleKernel, RejectsDegenerateTriangles) {
  const Vec3 a(0, 0, 0), b(1, 0, 0);
  EXPECT_FALSE(TriangleKernel::from(a, b, Vec3(2, 0, 0), nullptr));  // collinear
  EXPECT_FALSE(TriangleKernel::from(a, a, b, nullptr));              // repeated vertex
  EXPECT_FALSE(TriangleKernel::from(a, a, a, nullptr));
  EXPECT_FALSE(TriangleKernel::from(a, b, Vec3(0.5, 1e-17, 0), nullptr));  // below tolerance
  EXPECT_FALSE(TriangleKernel::from(a, b, Vec3(std::nan(""), 1, 0), nullptr));
  EXPECT_FALSE(TriangleKernel::from(a, b, Vec3(kInfinity, 1, 0), nullptr));
  EXPECT_TRUE(TriangleKernel::from(a, b, Vec3(0.5, 1e-9, 0), nullptr));  // thin but real
  // A triangle that is fine in double but collapses when rounded to float.
  EXPECT_TRUE(TriangleKernel::from(a, b, Vec3(0.5, 1e-12, 0), nullptr));
  EXPECT_FALSE(
      TriangleKernelFloat::from(Vec3(1, 1, 1), Vec3(2, 1, 1), Vec3(1.5, 1 + 1e-12, 1), nullptr));
}

TEST(TriangleKernel, SimpleHitFillsEveryField) {
  const auto tri = TriangleKernel::from(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), nullptr);
  ASSERT_TRUE(tri);
  SurfaceHit h;
  ASSERT_TRUE(tri->intersect(Ray{Vec3(0.25, 0.5, 2), Vec3(0, 0, -1)}, 0.0, kInfinity, h));
  EXPECT_DOUBLE_EQ(h.t, 2.0);
  EXPECT_DOUBLE_EQ(h.u, 0.25);  // weight of p1
  EXPECT_DOUBLE_EQ(h.v, 0.5);   // weight of p2
  EXPECT_EQ(h.geometric_normal, Vec3(0, 0, 1));
  EXPECT_EQ(h.shading_normal, Vec3(0, 0, 1));
  // Two-sided: from below as well, normal not flipped.
  ASSERT_TRUE(tri->intersect(Ray{Vec3(0.25, 0.5, -3), Vec3(0, 0, 1)}, 0.0, kInfinity, h));
  EXPECT_DOUBLE_EQ(h.t, 3.0);
  EXPECT_EQ(h.geometric_normal, Vec3(0, 0, 1));
  // The open interval (t_min, t_max) is respected.
  EXPECT_FALSE(tri->intersect(Ray{Vec3(0.25, 0.5, 2), Vec3(0, 0, -1)}, 0.0, 1.5, h));
  EXPECT_FALSE(tri->intersect(Ray{Vec3(0.25, 0.5, 2), Vec3(0, 0, -1)}, 2.5, kInfinity, h));
  EXPECT_FALSE(tri->intersect(Ray{Vec3(0.25, 0.5, 2), Vec3(0, 0, -1)}, 2.0, kInfinity, h));
  EXPECT_FALSE(tri->intersect(Ray{Vec3(0.25, 0.5, 2), Vec3(0, 0, 1)}, 0.0, kInfinity, h));
  // Edge-on: a ray in the triangle's plane never hits and produces nothing odd.
  EXPECT_FALSE(tri->intersect(Ray{Vec3(-1, 0.25, 0), Vec3(1, 0, 0)}, 0.0, kInfinity, h));
  const Bounds b = tri->bounds();
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));
  EXPECT_EQ(b.hi, Vec3(1, 1, 0));
}

TEST(TriangleKernel, ShadingNormalInterpolation) {
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  // Unnormalised vertex normals are normalised first.
  const Vec3 normals[3] = {Vec3(0, 0, 2), Vec3(3, 0, 3), Vec3(0, 0.5, 0.5)};
  const auto tri = TriangleKernel::from(p0, p1, p2, normals);
  ASSERT_TRUE(tri && tri->has_vertex_normals());
  SurfaceHit h;
  ASSERT_TRUE(tri->intersect(Ray{Vec3(0.5, 0.25, 1), Vec3(0, 0, -1)}, 0.0, kInfinity, h));
  const double s = std::sqrt(0.5);
  const Vec3 expected =
      glm::normalize(0.25 * Vec3(0, 0, 1) + 0.5 * Vec3(s, 0, s) + 0.25 * Vec3(0, s, s));
  EXPECT_NEAR(glm::length(h.shading_normal - expected), 0.0, 1e-15);
  EXPECT_EQ(h.geometric_normal, Vec3(0, 0, 1));

  // Normals that cancel at the hit fall back to the geometric normal.
  const Vec3 opposing[3] = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(-1, 0, 0)};
  const auto flat = TriangleKernel::from(p0, p1, p2, opposing);
  ASSERT_TRUE(flat);
  // Barycentric (0.5, 0.25, 0.25): 0.5*(1,0,0) + 0.5*(-1,0,0) = 0.
  ASSERT_TRUE(flat->intersect(Ray{Vec3(0.25, 0.25, 1), Vec3(0, 0, -1)}, 0.0, kInfinity, h));
  EXPECT_EQ(h.shading_normal, Vec3(0, 0, 1));
  EXPECT_TRUE(hit_is_sane(h));

  // A zero vertex normal disables interpolation (flat shading) instead of producing NaN.
  const Vec3 broken[3] = {Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 0, 1)};
  const auto b = TriangleKernel::from(p0, p1, p2, broken);
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->has_vertex_normals());
}

template <typename Kernel>
struct Agreement {
  int rays = 0, clear = 0, disagree = 0, hits = 0, insane = 0;
  double max_t_err = 0, max_uv_err = 0, max_n_err = 0;
};

// Random triangles, random rays aimed near them. On rays whose reference answer is clear (the
// hit point is farther than `margin` from every edge, the ray not grazing), the kernel must give
// the same hit/miss answer and the same t, u, v, normal within tolerances that follow from the
// precision: double ~1e-16 relative, so 1e-9 leaves room for the conditioning of random
// triangles; float ~6e-8, so 1e-3. The reference sees the ray the kernel sees (rounded to float
// for the float kernel): this isolates the kernel's arithmetic from the rounding of its input.
template <typename Kernel>
Agreement<Kernel> compare_with_reference(std::uint64_t seed, int triangles, int rays_per,
                                         double margin, long double grazing) {
  Agreement<Kernel> s;
  RandomGeometry g(seed);
  for (int i = 0; i < triangles; ++i) {
    const Vec3 p0 = g.in_box(1), p1 = g.in_box(1), p2 = g.in_box(1);
    const auto tri = Kernel::from(p0, p1, p2, nullptr);
    if (!tri) continue;
    const Vec3 q0 = tri->vertex(0), q1 = tri->vertex(1), q2 = tri->vertex(2);
    for (int j = 0; j < rays_per; ++j) {
      // Aim at a random affine combination around the triangle (about half hit).
      const double a = g.uniform(-0.3, 1.0), b = g.uniform(-0.3, 1.0);
      const Vec3 target = q0 + a * (q1 - q0) + b * (q2 - q0);
      const Vec3 origin = g.in_box(4);
      Ray ray = RandomGeometry::through(origin, target);
      using T = typename Kernel::Scalar;
      ray.origin = Vec3(Vec3T<T>(ray.origin));
      ray.direction = Vec3(Vec3T<T>(ray.direction));
      const double t_min = 1e-3, t_max = (j % 7 == 0) ? g.uniform(0, 6) : kInfinity;
      const Reference ref = reference(q0, q1, q2, ray, t_min, t_max, grazing);
      SurfaceHit h;
      const bool got = tri->intersect(ray, t_min, t_max, h);
      ++s.rays;
      if (got && !hit_is_sane(h)) ++s.insane;
      if (!ref.valid || std::fabs(ref.margin) < margin) continue;
      if (std::fabs(ref.t - t_min) < margin || std::fabs(ref.t - t_max) < margin) continue;
      ++s.clear;
      if (got != ref.hit) {
        ++s.disagree;
        continue;
      }
      if (!got) continue;
      ++s.hits;
      s.max_t_err = std::fmax(s.max_t_err, double(std::fabs(h.t - ref.t) / (1 + ref.t)));
      s.max_uv_err = std::fmax(s.max_uv_err, double(std::fabs(h.u - ref.u)));
      s.max_uv_err = std::fmax(s.max_uv_err, double(std::fabs(h.v - ref.v)));
      s.max_n_err =
          std::fmax(s.max_n_err, double(glm::length(LV(h.geometric_normal) - ref.normal)));
    }
  }
  return s;
}

TEST(TriangleKernel, DoubleAgreesWithReferenceOnRandomRays) {
  const auto s = compare_with_reference<TriangleKernel>(11, 2000, 100, 1e-9, 1e-6L);
  std::printf(
      "double: %d rays, %d clear, %d hits, disagreements %d (expected 0), max rel t err %.3g, "
      "max u/v err %.3g, max normal err %.3g (tolerance 1e-9)\n",
      s.rays, s.clear, s.hits, s.disagree, s.max_t_err, s.max_uv_err, s.max_n_err);
  EXPECT_GT(s.hits, s.clear / 5);
  EXPECT_EQ(s.disagree, 0);
  EXPECT_EQ(s.insane, 0);
  EXPECT_LT(s.max_t_err, 1e-9);
  EXPECT_LT(s.max_uv_err, 1e-9);
  EXPECT_LT(s.max_n_err, 1e-12);
}

TEST(TriangleKernel, FloatAgreesWithReferenceAwayFromEdges) {
  // Clear margin 1e-4 of a unit-sized scene (~1000 float ulps); rays within 1e-2 of grazing
  // (where the float hit point moves by ulp/cos) are left out.
  const auto s = compare_with_reference<TriangleKernelFloat>(12, 2000, 100, 1e-4, 1e-2L);
  std::printf(
      "float: %d rays, %d clear, %d hits, disagreements %d (expected 0), max rel t err %.3g, "
      "max u/v err %.3g (tolerance 1e-3)\n",
      s.rays, s.clear, s.hits, s.disagree, s.max_t_err, s.max_uv_err);
  EXPECT_GT(s.hits, s.clear / 5);
  EXPECT_EQ(s.disagree, 0);
  EXPECT_EQ(s.insane, 0);
  EXPECT_LT(s.max_t_err, 1e-3);
  EXPECT_LT(s.max_uv_err, 1e-3);
}

TEST(TriangleKernel, PublishedCost) {
  // The counts are documented line by line next to the kernel; this pins them and prints them.
  constexpr Cost c = TriangleKernel::kTestCost;
  constexpr Cost p = TriangleKernel::kPreparedTestCost;
  std::printf(
      "triangle test cost: %llu add, %llu mul, %llu div (ray setup per test included); "
      "%llu add, %llu mul, %llu div with a prepared ray\n",
      (unsigned long long)c.fp_add, (unsigned long long)c.fp_mul, (unsigned long long)c.fp_div,
      (unsigned long long)p.fp_add, (unsigned long long)p.fp_mul, (unsigned long long)p.fp_div);
  static_assert(c.fp_div == 2 && p.fp_div == 1 && c.fp_sqrt == 0);
  static_assert(TriangleKernel::kTestCost.mem_words ==
                2 * TriangleKernelFloat::kTestCost.mem_words);
}

TEST(TriangleKernel, ExactTiesAreSettledByTheTieRule) {
  // Two triangles sharing the edge (0,0,0)-(1,1,0); axis-aligned rays exactly through points of
  // the edge give edge functions that are exactly zero. Exactly one triangle must claim each.
  const Vec3 a(0, 0, 0), b(1, 1, 0), c(1, 0, 0), d(0, 1, 0);
  const auto t1 = TriangleKernel::from(a, c, b, nullptr);
  const auto t2 = TriangleKernel::from(a, b, d, nullptr);
  const auto f1 = TriangleKernelFloat::from(a, c, b, nullptr);
  const auto f2 = TriangleKernelFloat::from(a, b, d, nullptr);
  ASSERT_TRUE(t1 && t2 && f1 && f2);
  int bad = 0;
  for (int i = 1; i < 64; ++i) {
    const double s = i / 64.0;
    for (const Vec3 dir : {Vec3(0, 0, -1), Vec3(0, 0, 1)}) {
      const Ray ray{Vec3(s, s, -2 * dir.z), dir};
      SurfaceHit h;
      const int claims =
          int(t1->intersect(ray, 0, kInfinity, h)) + int(t2->intersect(ray, 0, kInfinity, h));
      const int fclaims =
          int(f1->intersect(ray, 0, kInfinity, h)) + int(f2->intersect(ray, 0, kInfinity, h));
      bad += (claims != 1) + (fclaims != 1);
    }
  }
  EXPECT_EQ(bad, 0);
}

}  // namespace
}  // namespace rtsim::kernels
