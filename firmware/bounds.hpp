#pragma once
#include <algorithm>

#include "firmware/math.hpp"
#include "firmware/ray.hpp"

namespace rtsim {

/// Axis-aligned box. An empty box has lo > hi.
struct Bounds {
  Vec3 lo{kInfinity};
  Vec3 hi{-kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  Vec3 extent() const { return hi - lo; }
  Vec3 center() const { return 0.5 * (lo + hi); }

  /// Slab test. Returns the parametric entry/exit clipped to [t_min, t_max]; false on a miss.
  /// Axis-parallel rays are handled by IEEE infinities (1/0 = inf); a zero-times-inf NaN from a
  /// ray lying exactly in a slab plane is treated as "inside that slab".
  bool intersect(const Ray& ray, double t_min, double t_max, double& t_enter,
                 double& t_exit) const {
    for (int a = 0; a < 3; ++a) {
      const double inv = 1.0 / ray.direction[a];
      double t0 = (lo[a] - ray.origin[a]) * inv;
      double t1 = (hi[a] - ray.origin[a]) * inv;
      if (t0 > t1) std::swap(t0, t1);
      if (!(t0 <= t1)) {  // NaN: origin on the slab plane with a zero direction component
        if (ray.origin[a] < lo[a] || ray.origin[a] > hi[a]) return false;
        continue;
      }
      t_min = std::max(t_min, t0);
      t_max = std::min(t_max, t1);
      if (t_min > t_max) return false;
    }
    t_enter = t_min;
    t_exit = t_max;
    return true;
  }
};

}  // namespace rtsim
