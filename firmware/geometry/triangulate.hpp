#pragma once
// Triangulation of a planar, possibly concave polygon (NFF `p` / `pp`) by ear clipping.
//
// Steps: Newell's normal (area-weighted, orientation of the input order) -> projection onto the
// coordinate plane where the polygon is largest, oriented so that the projected polygon is
// counter-clockwise -> removal of repeated consecutive vertices and of collinear vertices (straight
// runs and zero-width spikes) -> ear clipping with an inclusive point-in-triangle test and a
// convexity test that both carry a relative tolerance. An ear is tested only against the vertices
// a uniform grid (about one vertex per cell) puts near it, and each corner's convexity is kept
// as vertices are clipped: near-linear time for the polygons scenes hold (a 1,000,000-vertex
// circle or star in about a second), O(n^2) at worst (many vertices crowded into every ear).
//
// Output triangles index the ORIGINAL vertex array and are counter-clockwise about the Newell
// normal, i.e. they keep the input's winding (clockwise input gives a normal pointing the other
// way and triangles wound like the input). Removed vertices (duplicates, collinear) are used by no
// triangle. The seeds do not triangulate (Ullner needs convex quads: convex_quads.hpp merges these
// triangles into them); the tolerances below are assumptions, each with its reason.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/math.hpp"

namespace rtsim::geometry {

/// A polygon whose Newell area is <= this times its diameter^2 is rejected as zero-area. 1e-12:
/// far below any polygon a scene means to draw, above double rounding of the cross products.
inline constexpr double kPolygonDegenerateRelativeArea = 1e-12;

/// Largest distance of a vertex from the polygon's plane, relative to its diameter, before the
/// polygon is reported as non-planar (a warning; it is still triangulated). 1e-4: NFF files
/// print about 6 significant digits, so a planar polygon that is small against its distance from
/// the origin can be off its plane by ~1e-5 of its size; a warp of 1e-4 is still invisible.
inline constexpr double kNonPlanarRelativeTolerance = 1e-4;

/// Consecutive vertices closer than this, relative to the diameter, are one vertex. 1e-12 is a
/// few thousand double ulps: only copies and rounding-level near-copies merge.
inline constexpr double kDuplicateRelativeDistance = 1e-12;

/// A corner is collinear (straight run or spike) when |sin(turn angle)| <= this. 1e-10 keeps
/// circles of millions of vertices (turn ~1e-6) while removing rounding-level kinks.
inline constexpr double kCollinearRelativeSine = 1e-10;

/// Ear-clipping slack: a point counts as inside-or-on an ear when it is within this fraction of
/// the diameter of the ear's interior. Inclusive tests block borderline ears, which is safe.
inline constexpr double kEarContainmentRelative = 1e-10;

/// The triangles' total area must match the Newell area to this relative tolerance, or a warning
/// is issued. Rounding alone gives ~1e-15; 1e-6 only fires for self-crossing polygons.
inline constexpr double kAreaMismatchRelative = 1e-6;

/// Which ear is clipped next.
enum class EarChoice : std::uint8_t {
  /// The first ear found walking the outline, skipping one vertex after each clip: balanced,
  /// non-fan triangles on convex runs, O(n^2) at worst. The default (the triangle kernels).
  Walk,
  /// While at most kBestEarVertexLimit vertices remain, the ear whose triangle has the largest
  /// smallest angle (ties: first in input order); then as Walk. Well-shaped triangles that pair
  /// up into convex quads (convex_quads.hpp, Ullner's primitives); O(n^3) for small polygons.
  BestShaped,
};

/// EarChoice::BestShaped compares every ear while at most this many vertices remain (each step
/// costs O(n^2) ear tests), as the converter's own ear clipper did before it was replaced by
/// this one: polygons of up to 64 vertices are triangulated entirely on best-shaped ears.
inline constexpr std::size_t kBestEarVertexLimit = 64;

struct TriangulationResult {
  /// Index triples into the input vertex array, counter-clockwise about `normal`.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Vec3 normal{0.0};   ///< unit Newell normal (zero when rejected)
  double area = 0.0;  ///< polygon area from Newell's normal
  bool rejected = false;
  std::string reason;                 ///< why the polygon was rejected
  std::vector<std::string> warnings;  ///< non-planar polygon, forced ears (self-intersection)
  double plane_deviation = 0.0;       ///< largest distance from the plane / diameter
  std::size_t removed_duplicates = 0;
  std::size_t removed_collinear = 0;
  /// Vertices looked at by the ear tests: the work of ear clipping (tests/triangulate_test.cpp
  /// bounds it per vertex, so quadratic time on long polygons is caught without timing).
  std::size_t ear_vertex_tests = 0;
  /// The polygon crosses itself: rejected when two edges cross (self_crossing.hpp); set with the
  /// "no valid ear" or the area-mismatch warning when it passes through itself at a vertex (or
  /// is numerically degenerate), so the triangles may overlap or leave gaps. Callers that need a
  /// simple polygon (the convex-quad converter) reject it on this flag.
  bool not_simple = false;

  bool ok() const { return !rejected; }
};

/// Triangulates a planar polygon given in order (either winding). Never throws for bad geometry:
/// degenerate input comes back with `rejected` and a reason.
TriangulationResult triangulate_polygon(const std::vector<Vec3>& vertices,
                                        EarChoice choice = EarChoice::Walk);

}  // namespace rtsim::geometry
