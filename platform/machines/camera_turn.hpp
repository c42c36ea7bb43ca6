#pragma once
// A camera with its eye turned about the view's vertical axis (its up vector through the point
// it looks at): the camera paths of multi-frame runs (pxpl5-raytrace's camera.spin,
// ullner-scanline-tree's versions).
#include <cmath>

#include "firmware/math.hpp"
#include "firmware/scene.hpp"

namespace rtsim::platform {

/// `c` with its eye turned by `degrees` about the vertical axis through `c.at` (Rodrigues'
/// rotation); the point looked at and the up vector stay.
inline scenes::Camera turned_about_up(scenes::Camera c, double degrees) {
  const double a = degrees * kPi / 180.0;
  if (a == 0.0) return c;
  const Vec3 k = glm::normalize(c.up);
  const Vec3 v = c.from - c.at;
  c.from = c.at + v * std::cos(a) + glm::cross(k, v) * std::sin(a) +
           k * glm::dot(k, v) * (1.0 - std::cos(a));
  return c;
}

}  // namespace rtsim::platform
