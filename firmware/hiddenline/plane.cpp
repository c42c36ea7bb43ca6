#include "firmware/hiddenline/plane.hpp"

#include <cstdlib>

namespace rtsim::hiddenline {

std::vector<Plane> boundary_planes(const std::vector<ScreenPoint>& poly) {
  if (poly.size() < 3) return {};
  // The polygon's plane from its first vertex and the two that span the most area (the others
  // lie on it, up to the integer rounding of the transformation).
  const auto sub = [](const ScreenPoint& p, const ScreenPoint& q) {
    return std::array<std::int64_t, 3>{std::int64_t{p[0]} - q[0], std::int64_t{p[1]} - q[1],
                                       std::int64_t{p[2]} - q[2]};
  };
  Plane own;
  std::int64_t best = 0;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
    const auto u = sub(poly[i], poly[0]), w = sub(poly[i + 1], poly[0]);
    const std::int64_t a = u[1] * w[2] - u[2] * w[1], b = u[2] * w[0] - u[0] * w[2],
                       c = u[0] * w[1] - u[1] * w[0];
    if (std::llabs(c) > best) {
      best = std::llabs(c);
      own = {a, b, c, 0, true};
    }
  }
  // Edge-on (no area on the screen): it hides nothing.
  if (own.c == 0) return {};
  own.d = -(own.a * poly[0][0] + own.b * poly[0][1] + own.c * poly[0][2]);
  // The visible side is towards the eye, where z is smaller: the value must grow as z falls.
  if (own.c > 0) own = {-own.a, -own.b, -own.c, -own.d, true};
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const ScreenPoint& p = poly[i];
    const ScreenPoint& q = poly[(i + 1) % poly.size()];
    Plane e{std::int64_t{q[1]} - p[1], -(std::int64_t{q[0]} - p[0]), 0, 0, false};
    e.d = -(e.a * p[0] + e.b * p[1]);
    if (e.a == 0 && e.b == 0) continue;  // a repeated vertex
    // The polygon's inside on the negative side: the vertex farthest from the edge's line.
    std::int64_t far = 0;
    for (const ScreenPoint& r : poly)
      if (std::llabs(e.at(r)) > std::llabs(far)) far = e.at(r);
    if (far > 0) e = {-e.a, -e.b, 0, -e.d, false};
    planes.push_back(e);
  }
  planes.push_back(own);
  return planes;
}

}  // namespace rtsim::hiddenline
