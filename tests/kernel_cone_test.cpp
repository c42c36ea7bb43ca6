// Cone/cylinder kernel against an independent reference: the quadratic written directly in world
// coordinates (distance from the axis, no local frame, no origin shift, textbook root formula)
// and evaluated in long double.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "firmware/kernels/cone.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::kernels {
namespace {

using testing::hit_is_sane;
using testing::RandomGeometry;
using LV = glm::vec<3, long double, glm::defaultp>;

TEST(ConeKernel, RejectsDegenerateConesWithAReason) {
  std::string why;
  EXPECT_FALSE(ConeKernel::from({Vec3(1, 2, 3), 1.0, Vec3(1, 2, 3), 2.0}, &why));
  EXPECT_NE(why.find("coincide"), std::string::npos) << why;
  EXPECT_FALSE(ConeKernel::from({Vec3(1e6, 0, 0), 1.0, Vec3(1e6, 1e-8, 0), 2.0}, &why));
  EXPECT_NE(why.find("coincide"), std::string::npos) << why;
  EXPECT_FALSE(ConeKernel::from({Vec3(0), 0.0, Vec3(0, 0, 1), -0.0}, &why));
  EXPECT_NE(why.find("both cone radii are zero"), std::string::npos) << why;
  EXPECT_FALSE(ConeKernel::from({Vec3(0), std::nan(""), Vec3(0, 0, 1), 1.0}, &why));
  EXPECT_FALSE(ConeKernel::from({Vec3(0, 0, kInfinity), 1.0, Vec3(0, 0, 1), 1.0}, &why));
  EXPECT_TRUE(ConeKernel::from({Vec3(0), 1.0, Vec3(0, 0, 1), 0.0}));  // a true cone
  EXPECT_TRUE(ConeKernel::from({Vec3(0), 0.0, Vec3(0, 0, 1), 1.0}));  // point at the base
}

TEST(ConeKernel, CylinderBasics) {
  const auto cyl = ConeKernel::from({Vec3(0, 0, 0), 1.0, Vec3(0, 0, 2), 1.0});
  ASSERT_TRUE(cyl && cyl->is_cylinder());
  SurfaceHit h;
  ASSERT_TRUE(cyl->intersect(Ray{Vec3(5, 0, 1), Vec3(-1, 0, 0)}, 0.0, kInfinity, h));
  EXPECT_NEAR(h.t, 4.0, 1e-15);
  EXPECT_NEAR(glm::length(h.geometric_normal - Vec3(1, 0, 0)), 0.0, 1e-15);
  EXPECT_NEAR(h.v, 0.5, 1e-15);
  // From inside: the wall, normal still outward (surfaces are two-sided, normals not flipped).
  ASSERT_TRUE(cyl->intersect(Ray{Vec3(0, 0, 1), Vec3(0, 1, 0)}, 0.0, kInfinity, h));
  EXPECT_NEAR(h.t, 1.0, 1e-15);
  EXPECT_NEAR(glm::length(h.geometric_normal - Vec3(0, 1, 0)), 0.0, 1e-15);
  // No end caps: above the top, and straight along the axis, nothing is hit.
  EXPECT_FALSE(cyl->intersect(Ray{Vec3(5, 0, 3), Vec3(-1, 0, 0)}, 0.0, kInfinity, h));
  EXPECT_FALSE(cyl->intersect(Ray{Vec3(0.5, 0, -1), Vec3(0, 0, 1)}, 0.0, kInfinity, h));
  // A ray lying in the surface (a == b == c == 0) is rejected without NaN.
  EXPECT_FALSE(cyl->intersect(Ray{Vec3(1, 0, -1), Vec3(0, 0, 1)}, 0.0, kInfinity, h));
  // Through the open top at a slant: enters through the top, hits the far wall from inside.
  ASSERT_TRUE(
      cyl->intersect(Ray{Vec3(0, 0, 3), glm::normalize(Vec3(1, 0, -1))}, 0.0, kInfinity, h));
  EXPECT_NEAR(h.t, std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(h.v, 1.0, 1e-14);
  const Bounds b = cyl->bounds();
  EXPECT_NEAR(glm::length(b.lo - Vec3(-1, -1, 0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(b.hi - Vec3(1, 1, 2)), 0.0, 1e-15);
}

TEST(ConeKernel, SlantedNormalsApexAndNegativeRadii) {
  // 45-degree cone: radius 1 at z = 0, point at z = 1. NFF negative radius = same geometry.
  for (double sign : {1.0, -1.0}) {
    const auto cone = ConeKernel::from({Vec3(0, 0, 0), sign * 1.0, Vec3(0, 0, 1), 0.0});
    ASSERT_TRUE(cone);
    SurfaceHit h;
    ASSERT_TRUE(cone->intersect(Ray{Vec3(5, 0, 0.5), Vec3(-1, 0, 0)}, 0.0, kInfinity, h));
    EXPECT_NEAR(h.t, 4.5, 1e-14);
    const Vec3 expected = glm::normalize(Vec3(1, 0, 1));
    EXPECT_NEAR(glm::length(h.geometric_normal - expected), 0.0, 1e-15);
    // A ray parallel to a slant line (a == 0): one root, at s = 0.98 along the line.
    const Vec3 d = glm::normalize(Vec3(-1, 0, 1));
    ASSERT_TRUE(cone->intersect(Ray{Vec3(0.5, 0.2, -0.5), d}, 0.0, kInfinity, h));
    EXPECT_NEAR(h.t, 0.98 * std::sqrt(2.0), 1e-14);
    EXPECT_TRUE(hit_is_sane(h));
    // Straight down the axis into the point: a hit exactly at the apex, finite normal.
    ASSERT_TRUE(cone->intersect(Ray{Vec3(0, 0, 2), Vec3(0, 0, -1)}, 0.0, kInfinity, h));
    EXPECT_NEAR(h.t, 1.0, 1e-15);
    EXPECT_TRUE(hit_is_sane(h));
  }
  // Frustum with the wider end at the apex: the normal leans toward the base (-z).
  const auto f = ConeKernel::from({Vec3(0, 0, 0), 1.0, Vec3(0, 0, 1), 2.0});
  ASSERT_TRUE(f);
  SurfaceHit h;
  ASSERT_TRUE(f->intersect(Ray{Vec3(0, 5, 0.5), Vec3(0, -1, 0)}, 0.0, kInfinity, h));
  EXPECT_NEAR(h.t, 3.5, 1e-14);
  EXPECT_NEAR(glm::length(h.geometric_normal - glm::normalize(Vec3(0, 1, -1))), 0.0, 1e-15);
}

struct RefHit {
  bool hit = false;
  bool borderline = false;
  long double t = 0;
  LV normal{0};
};

RefHit reference(const scenes::Cone& cone, const Ray& ray, double t_min, double t_max) {
  RefHit r;
  const LV base(cone.base), apex(cone.apex), o(ray.origin), d(ray.direction);
  const long double h = glm::length(apex - base);
  const LV w = (apex - base) / h;
  const long double r0 = std::fabs((long double)cone.base_radius);
  const long double r1 = std::fabs((long double)cone.apex_radius);
  const long double k = (r1 - r0) / h;
  const LV m = o - base;
  const long double q1 = glm::dot(m, w), q2 = glm::dot(d, w);
  const LV mp = m - q1 * w, dp = d - q2 * w;
  const long double rho = r0 + k * q1;
  const long double A = glm::dot(dp, dp) - k * k * q2 * q2;
  const long double B = 2 * (glm::dot(mp, dp) - k * q2 * rho);
  const long double C = glm::dot(mp, mp) - rho * rho;
  const long double disc = B * B - 4 * A * C;
  const long double tol = 1e-9L;
  if (std::fabs(A) < tol || std::fabs(disc) < tol * (B * B + std::fabs(4 * A * C))) {
    r.borderline = true;
  }
  if (disc < 0) return r;
  const long double sq = std::sqrt(disc);
  long double t0 = (-B - sq) / (2 * A), t1 = (-B + sq) / (2 * A);
  if (t0 > t1) std::swap(t0, t1);
  for (long double t : {t0, t1}) {
    const long double z = q1 + t * q2;
    if (std::fabs(z) < tol * h || std::fabs(z - h) < tol * h) r.borderline = true;
    if (std::fabs(t - t_min) < tol || std::fabs(t - t_max) < tol) r.borderline = true;
    if (!r.hit && t > t_min && t < t_max && z >= 0 && z <= h) {
      r.hit = true;
      r.t = t;
      // Gradient of |p_perp|^2 - rho(z)^2: 2 p_perp - 2 rho(z) k w.
      const LV pp = mp + t * dp;
      const LV g = pp - (r0 + k * z) * k * w;
      r.normal = g / glm::length(g);
    }
  }
  return r;
}

TEST(ConeKernel, AgreesWithWorldSpaceReferenceOnRandomRays) {
  RandomGeometry g(31);
  int rays = 0, clear = 0, disagree = 0, hits = 0, insane = 0;
  double max_t = 0, max_n = 0;
  for (int i = 0; i < 2000; ++i) {
    scenes::Cone cone;
    cone.base = g.in_box(2);
    cone.apex = cone.base + g.uniform(0.2, 3.0) * g.unit();
    switch (i % 4) {
      case 0:  // cylinder
        cone.base_radius = cone.apex_radius = g.uniform(0.1, 1.5);
        break;
      case 1:  // true cone, point at either end
        cone.base_radius = g.uniform(0.1, 1.5);
        cone.apex_radius = 0.0;
        if (i % 8 == 1) std::swap(cone.base_radius, cone.apex_radius);
        break;
      case 2:  // frustum
        cone.base_radius = g.uniform(0.1, 1.5);
        cone.apex_radius = g.uniform(0.1, 1.5);
        break;
      default:  // NFF "seen from inside": negative radii
        cone.base_radius = -g.uniform(0.1, 1.5);
        cone.apex_radius = -g.uniform(0.0, 1.5);
        break;
    }
    const auto k = ConeKernel::from(cone);
    ASSERT_TRUE(k);
    const Vec3 centre = 0.5 * (cone.base + cone.apex);
    const double reach = 0.5 * glm::length(cone.apex - cone.base) +
                         std::fmax(std::fabs(cone.base_radius), std::fabs(cone.apex_radius));
    for (int j = 0; j < 100; ++j) {
      const Vec3 origin = g.in_box(6);
      const Ray ray = RandomGeometry::through(origin, centre + reach * g.uniform(0, 1) * g.unit());
      const double t_min = (j % 5 == 0) ? g.uniform(0, 8) : 1e-6;
      const double t_max = (j % 7 == 0) ? g.uniform(0, 10) : kInfinity;
      const RefHit ref = reference(cone, ray, t_min, t_max);
      SurfaceHit h;
      const bool got = k->intersect(ray, t_min, t_max, h);
      ++rays;
      if (got && !hit_is_sane(h)) ++insane;
      if (ref.borderline) continue;
      ++clear;
      if (got != ref.hit) {
        ++disagree;
        continue;
      }
      if (!got) continue;
      ++hits;
      max_t = std::fmax(max_t, double(std::fabs(h.t - ref.t) / (1 + ref.t)));
      max_n = std::fmax(max_n, double(glm::length(LV(h.geometric_normal) - ref.normal)));
    }
  }
  std::printf(
      "cone: %d rays, %d clear, %d hits, disagreements %d (expected 0), max rel t err %.3g, "
      "max normal err %.3g (tolerance 1e-10)\n",
      rays, clear, hits, disagree, max_t, max_n);
  EXPECT_GT(hits, clear / 5);
  EXPECT_EQ(disagree, 0);
  EXPECT_EQ(insane, 0);
  EXPECT_LT(max_t, 1e-10);
  EXPECT_LT(max_n, 1e-10);
}

}  // namespace
}  // namespace rtsim::kernels
