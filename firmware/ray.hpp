#pragma once
#include <cstdint>

#include "firmware/math.hpp"

namespace rtsim {

/// A ray r(t) = origin + t * direction with a unit-length direction, so t is a distance.
/// (Ullner writes r(t) = (r1 - r0) t + r0, seed 000 L271; with r1 = r0 + direction the two agree.)
struct Ray {
  Vec3 origin{0.0};
  Vec3 direction{0.0, 0.0, 1.0};

  Vec3 at(double t) const { return origin + t * direction; }
};

/// What a ray is for; the statistics count rays by kind.
enum class RayKind : std::uint8_t { Primary, Shadow, Reflected, Refracted };

}  // namespace rtsim
