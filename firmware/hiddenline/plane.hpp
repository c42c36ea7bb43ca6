#pragma once
// A convex polygon's hidden volume as boundary planes (seed 000 L1701-L1711, Fig. 3-28): one
// plane through each edge, perpendicular to the screen, and the polygon's own plane. Each plane
// a x + b y + c z + d = 0 is oriented so that its positive side is the visible one: outside the
// edge, in front of the polygon (towards the eye, smaller z). A point is hidden by the polygon
// only if it is on the negative side of every one of its planes; a point on a plane counts as
// visible (L1767-L1769: "t_n >= 0"), so an edge is never hidden by its own polygon or by a
// neighbour sharing it. The coefficients are exact integers: with coordinates below 2^16, a, b
// and c are below 2^33 and d below 2^51.
#include <cstdint>
#include <vector>

#include "firmware/hiddenline/messages.hpp"

namespace rtsim::hiddenline {

struct Plane {
  std::int64_t a = 0, b = 0, c = 0, d = 0;
  /// f: the last plane of its polygon (L1801-L1803): its processor marks the intersections
  /// leaving it as the ends of a hidden part.
  bool last = false;

  std::int64_t at(const ScreenPoint& p) const { return a * p[0] + b * p[1] + c * p[2] + d; }
};

/// The polygon's edge planes in vertex order, then its own plane (marked last). Nothing for a
/// polygon that hides no volume: fewer than three vertices, or seen edge-on (its own plane
/// perpendicular to the screen). The polygon must be convex (L1898: concave ones are split).
std::vector<Plane> boundary_planes(const std::vector<ScreenPoint>& polygon);

}  // namespace rtsim::hiddenline
