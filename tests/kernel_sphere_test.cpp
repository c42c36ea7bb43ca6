// Sphere kernel against an independent reference: the textbook quadratic formula evaluated in
// long double (64-bit mantissa), which is accurate for the moderate origins used here.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "firmware/kernels/sphere.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::kernels {
namespace {

using testing::hit_is_sane;
using testing::RandomGeometry;
using LV = glm::vec<3, long double, glm::defaultp>;

TEST(SphereKernel, RejectsBadSpheresWithAReason) {
  std::string why;
  EXPECT_FALSE(SphereKernel::from({Vec3(0), 0.0}, &why));
  EXPECT_NE(why.find("not positive"), std::string::npos) << why;
  EXPECT_FALSE(SphereKernel::from({Vec3(0), -1.0}, &why));
  EXPECT_FALSE(SphereKernel::from({Vec3(0), std::nan("")}, &why));
  EXPECT_NE(why.find("not finite"), std::string::npos) << why;
  EXPECT_FALSE(SphereKernel::from({Vec3(0, kInfinity, 0), 1.0}, &why));
  EXPECT_FALSE(SphereKernel::from({Vec3(0), 1e200}, &why));  // r^2 overflows
  EXPECT_TRUE(SphereKernel::from({Vec3(0), 1e-100}));
}

TEST(SphereKernel, NearRootFarRootAndInterval) {
  const auto s = SphereKernel::from({Vec3(0, 0, 0), 2.0});
  ASSERT_TRUE(s);
  SurfaceHit h;
  const Ray ray{Vec3(0, 0, 10), Vec3(0, 0, -1)};
  ASSERT_TRUE(s->intersect(ray, 0.0, kInfinity, h));
  EXPECT_DOUBLE_EQ(h.t, 8.0);
  EXPECT_EQ(h.geometric_normal, Vec3(0, 0, 1));
  ASSERT_TRUE(s->intersect(ray, 8.5, kInfinity, h));  // first root excluded: the far one
  EXPECT_DOUBLE_EQ(h.t, 12.0);
  EXPECT_EQ(h.geometric_normal, Vec3(0, 0, -1));
  EXPECT_FALSE(s->intersect(ray, 12.0, kInfinity, h));
  EXPECT_FALSE(s->intersect(ray, 0.0, 8.0, h));
  // Origin inside: the exit point, normal outward.
  ASSERT_TRUE(s->intersect(Ray{Vec3(0, 0, 0), Vec3(1, 0, 0)}, 0.0, kInfinity, h));
  EXPECT_DOUBLE_EQ(h.t, 2.0);
  EXPECT_EQ(h.geometric_normal, Vec3(1, 0, 0));
  // Behind the origin: miss.
  EXPECT_FALSE(s->intersect(Ray{Vec3(0, 0, 10), Vec3(0, 0, 1)}, 0.0, kInfinity, h));
  // Exactly tangent: a (double) hit at the tangent point, finite.
  ASSERT_TRUE(s->intersect(Ray{Vec3(2, 0, 10), Vec3(0, 0, -1)}, 0.0, kInfinity, h));
  EXPECT_DOUBLE_EQ(h.t, 10.0);
  EXPECT_TRUE(hit_is_sane(h));
  EXPECT_EQ(h.geometric_normal, Vec3(1, 0, 0));
  // Origin exactly on the surface, ray tangent: q == 0, c/q is NaN; no NaN may escape.
  const bool on = s->intersect(Ray{Vec3(2, 0, 0), Vec3(0, 0, 1)}, -1.0, kInfinity, h);
  if (on) {
    EXPECT_TRUE(hit_is_sane(h));
  }
  const Bounds b = s->bounds();
  EXPECT_EQ(b.lo, Vec3(-2));
  EXPECT_EQ(b.hi, Vec3(2));
}

TEST(SphereKernel, AgreesWithLongDoubleReferenceOnRandomRays) {
  RandomGeometry g(21);
  int rays = 0, clear = 0, disagree = 0, hits = 0, insane = 0;
  double max_t = 0, max_n = 0;
  for (int i = 0; i < 2000; ++i) {
    const scenes::Sphere sph{g.in_box(2), g.uniform(0.05, 1.5)};
    const auto k = SphereKernel::from(sph);
    ASSERT_TRUE(k);
    for (int j = 0; j < 100; ++j) {
      const Vec3 origin = g.in_box(5);
      const Ray ray = RandomGeometry::through(origin, sph.center + 1.3 * sph.radius * g.unit());
      const double t_min = (j % 5 == 0) ? g.uniform(0, 8) : 1e-6;
      const double t_max = (j % 7 == 0) ? g.uniform(0, 8) : kInfinity;
      // Reference: a t^2 + 2 b t + c = 0.
      const LV o(ray.origin), d(ray.direction), c(sph.center);
      const LV oc = o - c;
      const long double a = glm::dot(d, d), b = glm::dot(d, oc);
      const long double cc = glm::dot(oc, oc) - (long double)sph.radius * sph.radius;
      const long double disc = b * b - a * cc;
      bool ref_hit = false;
      long double ref_t = 0;
      bool borderline = std::fabs(disc) < 1e-9L * (b * b + std::fabs(a * cc));
      if (disc >= 0) {
        const long double sq = std::sqrt(disc);
        for (long double t : {(-b - sq) / a, (-b + sq) / a}) {
          if (std::fabs(t - t_min) < 1e-9L || std::fabs(t - t_max) < 1e-9L) borderline = true;
          if (!ref_hit && t > t_min && t < t_max) {
            ref_hit = true;
            ref_t = t;
          }
        }
      }
      SurfaceHit h;
      const bool got = k->intersect(ray, t_min, t_max, h);
      ++rays;
      if (got && !hit_is_sane(h)) ++insane;
      if (borderline) continue;
      ++clear;
      if (got != ref_hit) {
        ++disagree;
        continue;
      }
      if (!got) continue;
      ++hits;
      max_t = std::fmax(max_t, double(std::fabs(h.t - ref_t) / (1 + ref_t)));
      const LV n_ref = (o + ref_t * d - c) / (long double)sph.radius;
      max_n = std::fmax(max_n, double(glm::length(LV(h.geometric_normal) - n_ref)));
    }
  }
  std::printf(
      "sphere: %d rays, %d clear, %d hits, disagreements %d (expected 0), max rel t err %.3g, "
      "max normal err %.3g (tolerance 1e-12)\n",
      rays, clear, hits, disagree, max_t, max_n);
  EXPECT_GT(hits, clear / 4);
  EXPECT_EQ(disagree, 0);
  EXPECT_EQ(insane, 0);
  EXPECT_LT(max_t, 1e-12);
  EXPECT_LT(max_n, 1e-12);
}

}  // namespace
}  // namespace rtsim::kernels
