#pragma once
// Whether a polygon's outline crosses itself, in O(n log n): the Shamos-Hoey sweep over its
// edges, with exact predicates on the vertices snapped to an integer grid.
//
// Two edges that do not share a vertex cross when each passes strictly through the other.
// Edges that only touch do not count: a vertex on another edge, two vertices at one place, or
// two edges along each other (a keyhole's bridge, out to a hole and back). Such outlines bound
// an interior that ear clipping tiles; its area check (triangulate.hpp) still catches an outline
// that passes through itself at a vertex.
//
// The sweep keeps the edges that meet a vertical line in their order along it, and tests each
// edge against its neighbours as the line passes the vertices; the leftmost crossing is found
// before the line reaches it (Shamos and Hoey, 1976). Its order comparisons must be exact, so the
// vertices are first snapped to a grid of 2^29 steps either side of the polygon's centre, where
// the orientation of three points is computed exactly in 64-bit integers. Features closer than
// about 2e-9 of the polygon's size are judged as snapped.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace rtsim::geometry {

/// A point of the projected polygon (triangulate.cpp's 2-D coordinates).
struct Point2 {
  double x = 0.0, y = 0.0;
};

/// Indices i < j of two edges that cross (edge k joins vertex k to vertex k+1, cyclically), or
/// nothing for an outline that does not cross itself. Vertices must be finite.
std::optional<std::pair<std::size_t, std::size_t>> first_self_crossing(
    const std::vector<Point2>& outline);

}  // namespace rtsim::geometry
