#pragma once
// A uniformly random orientation for the generators (Ullner's "randomly oriented" cubes and
// squares, seed 000 L668), from the project's own SplitMix64 so that a seed gives the same scene
// with any standard library.
#include <array>
#include <cmath>

#include "common/splitmix64.hpp"
#include "firmware/math.hpp"

namespace rtsim::scenes {

/// Rotation matrix columns from a unit quaternion (w, x, y, z).
inline std::array<Vec3, 3> rotation_of(double w, double x, double y, double z) {
  return {Vec3{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
          Vec3{2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
          Vec3{2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
}

/// The three axes of a uniformly random rotation: a point uniform in the 4-ball (rejection from
/// the cube [-1,1]^4), normalised, is a uniform unit quaternion. Only +, *, sqrt: the same on
/// every libm.
inline std::array<Vec3, 3> random_rotation(SplitMix64& rng) {
  double q[4];
  double norm2 = 0.0;
  do {
    norm2 = 0.0;
    for (double& c : q) {
      c = rng.uniform(-1.0, 1.0);
      norm2 += c * c;
    }
  } while (norm2 > 1.0 || norm2 < 1e-6);
  const double inv = 1.0 / std::sqrt(norm2);
  return rotation_of(q[0] * inv, q[1] * inv, q[2] * inv, q[3] * inv);
}

}  // namespace rtsim::scenes
