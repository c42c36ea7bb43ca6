#pragma once
// Ray/sphere intersection. A sphere is a quadric (seed 000 L943-L953: substitute the parametric
// ray into the surface equation and solve the quadratic "by the quadratic formula"); this kernel
// solves that quadratic in a numerically stable way:
//
//   |o + t d - c|^2 = r^2,  |d| = 1   =>   t^2 + 2 b' t + c' = 0,
//   b' = d . (o - c)  (half b),   c' = |o - c|^2 - r^2.
//
// * Discriminant in geometric form: b'^2 - c' = r^2 - |(o - c) - b' d|^2. The vector
//   f = (o - c) - b' d runs from the centre to the point of the ray closest to it, so its length
//   is of the order of r even when the origin is far away, where b'^2 - c' would cancel
//   catastrophically (both terms ~|o - c|^2).
// * Roots without cancellation: q = -b' - sgn(b') sqrt(disc), t = q and t = c'/q.
// * Normal without cancellation: at a root, p - c = f + (t + b') d = f -+ sqrt(disc) d (minus for
//   the near root, plus for the far one), all of size r, then normalised.
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "firmware/bounds.hpp"
#include "firmware/cost.hpp"
#include "firmware/hit.hpp"
#include "firmware/math.hpp"
#include "firmware/ray.hpp"
#include "firmware/scene.hpp"

namespace rtsim::kernels {

class SphereKernel {
 public:
  /// nullopt (and a reason in *why, if given) for a non-finite centre or a radius that is not a
  /// finite positive number.
  static std::optional<SphereKernel> from(const scenes::Sphere& sphere, std::string* why = nullptr);

  /// Nearest root in (t_min, t_max). Fills t and the unit normal (p - c)/|p - c|, outward, as both
  /// the geometric and the shading normal. u and v are left 0 (NFF has no texture coordinates).
  bool intersect(const Ray& ray, double t_min, double t_max, SurfaceHit& hit) const {
    const Vec3& d = ray.direction;
    const Vec3 oc = ray.origin - center_;      // 3 adds
    const double b = glm::dot(d, oc);          // 3 mul, 2 add
    const Vec3 f = oc - b * d;                 // 3 mul, 3 add: centre -> closest point of the ray
    const double disc = r2_ - glm::dot(f, f);  // 3 mul, 3 add
    if (!(disc >= 0.0)) return false;          // 1 compare (also rejects NaN)
    const double c = glm::dot(oc, oc) - r2_;   // 3 mul, 3 add
    const double sq = std::sqrt(disc);         // 1 sqrt
    const double q = (b >= 0.0) ? -(b + sq) : (sq - b);  // 1 compare, 1 add
    double t_near = q;                                   // a = 1: root q/a = q
    double t_far = c / q;                                // 1 divide (NaN/inf if q == 0)
    if (t_near > t_far) std::swap(t_near, t_far);        // 1 compare
    double t;
    double side;  // -1: near root, p - c = f - sq d;  +1: far root, p - c = f + sq d
    if (t_near > t_min && t_near < t_max) {  // 2 compares
      t = t_near;
      side = -1.0;
    } else if (t_far > t_min && t_far < t_max) {
      t = t_far;
      side = 1.0;
    } else {
      return false;
    }
    if (!std::isfinite(t)) return false;
    // p - c, of length r up to rounding; normalised rather than divided by r because from far
    // away f carries an absolute error of ~ulp(|o - c|), which near tangency would leave |n|
    // off 1 by more than rounding.
    const Vec3 pc = f + (side * sq) * d;   // 1 mul, 3 mul, 3 add
    const double len2 = glm::dot(pc, pc);  // 3 mul, 2 add
    if (!(len2 > 0.0)) return false;
    const Vec3 n = pc * (1.0 / std::sqrt(len2));  // 1 sqrt, 1 divide, 3 mul
    if (!is_finite(n)) return false;
    hit.t = t;
    hit.u = 0.0;
    hit.v = 0.0;
    hit.geometric_normal = n;
    hit.shading_normal = n;
    return true;
  }

  Bounds bounds() const {
    Bounds bx;
    bx.extend(center_ - Vec3(radius_));
    bx.extend(center_ + Vec3(radius_));
    return bx;
  }

  const Vec3& center() const { return center_; }
  double radius() const { return radius_; }

  /// Cost of a test that hits, counted line by line from intersect above (a = add/compare,
  /// m = multiply): oc 3a; b 3m 2a; f 3m 3a; disc 3m 3a; disc >= 0 1a; c 3m 3a; sqrt; q 2a;
  /// c/q 1 divide; order 1a; range 2a; normal: p - c 4m 3a, |p - c|^2 3m 2a 1a (> 0), sqrt,
  /// divide, 3m. A ray that misses on the discriminant stops after 12 adds and 9 multiplies.
  /// mem_words: centre (3) and r^2, as doubles: 4 * 2.
  static constexpr Cost kTestCost{.fp_add = 3 + 2 + 3 + 3 + 1 + 3 + 2 + 1 + 2 + 3 + 3,
                                  .fp_mul = 3 + 3 + 3 + 3 + 4 + 3 + 3,
                                  .fp_div = 2,
                                  .fp_sqrt = 2,
                                  .mem_words = 8,
                                  .instructions = 8};

 private:
  SphereKernel() = default;

  Vec3 center_{0.0};
  double radius_ = 1.0;
  double r2_ = 1.0;
};

}  // namespace rtsim::kernels
