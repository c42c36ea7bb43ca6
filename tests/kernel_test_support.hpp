#pragma once
// Small helpers shared by the kernel and acceleration tests (and bench/accel_bench.cpp):
// deterministic random rays, a plain ray/sphere root and hit sanity checks.
#include <cmath>
#include <cstdint>
#include <random>

#include "firmware/hit.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"

namespace rtsim::testing {

/// Smallest t of the ray/sphere intersection in (t_min, t_max), +inf if none: the plain
/// quadratic (unit direction), an oracle for the acceleration structures' tests and benchmarks
/// independent of the firmware's SphereKernel.
inline double sphere_root(const Vec3& centre, double radius, const Ray& ray, double t_min,
                          double t_max) {
  const Vec3 oc = ray.origin - centre;
  const double b = glm::dot(oc, ray.direction);
  const double c = glm::dot(oc, oc) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return kInfinity;
  const double q = std::sqrt(disc);
  if (const double t = -b - q; t > t_min && t < t_max) return t;
  if (const double t = -b + q; t > t_min && t < t_max) return t;
  return kInfinity;
}

/// Deterministic source of random geometry (fixed seed per test, so failures reproduce).
class RandomGeometry {
 public:
  explicit RandomGeometry(std::uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  Vec3 in_box(double half) {
    return {uniform(-half, half), uniform(-half, half), uniform(-half, half)};
  }
  Vec3 unit() {
    for (;;) {
      const Vec3 v = in_box(1.0);
      const double l = glm::length(v);
      if (l > 1e-3 && l <= 1.0) return v / l;
    }
  }
  /// A ray from `origin` through `target`.
  static Ray through(const Vec3& origin, const Vec3& target) {
    return Ray{origin, glm::normalize(target - origin)};
  }
  std::mt19937_64& engine() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

/// Everything a kernel reports must be finite and the normals unit length.
inline bool hit_is_sane(const SurfaceHit& h) {
  return std::isfinite(h.t) && std::isfinite(h.u) && std::isfinite(h.v) &&
         is_finite(h.geometric_normal) && is_finite(h.shading_normal) &&
         std::fabs(glm::length(h.geometric_normal) - 1.0) < 1e-9 &&
         std::fabs(glm::length(h.shading_normal) - 1.0) < 1e-9;
}

}  // namespace rtsim::testing
