#pragma once
// Turning scene polygons into Ullner's primitives (seed 000 L267: "only convex quadrilaterals
// will be considered. These may, of course, be pieced together in order to form arbitrarily
// complicated polygons"). A planar polygon -- possibly concave, with optional per-vertex normals
// -- is cleaned up and cut into triangles by triangulate_polygon (triangulate.hpp: duplicate and
// collinear vertices removed, ear clipping), and adjacent triangle pairs are merged greedily into
// convex quads where the pair is coplanar and the quad convex. A triangle that stays alone is
// given as a quad with two equal vertices (p11 == p01), which the Ullner kernel supports.
//
// Bad input is repaired or rejected, never passed on: the report counts every case by reason.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/math.hpp"

namespace rtsim::geometry {

/// One Ullner primitive: corners p00, p10, p11, p01 (counter-clockwise about the polygon's
/// normal, seed 000 L283), and the corner normals n00, n10, n11, n01 when the polygon has them.
struct ConvexQuad {
  std::array<Vec3, 4> corners{};
  std::array<Vec3, 4> normals{};
  bool has_normals = false;
  bool triangle = false;  ///< a triangle given as a quad: corners[2] == corners[3]
};

/// What was repaired in a polygon (a polygon may need several).
enum class PolygonRepair : std::uint8_t {
  DuplicateVertex,  ///< consecutive equal vertices merged
  CollinearVertex,  ///< a vertex on a straight line (or a zero-width spike) removed
  NonPlanar,        ///< not planar within tolerance: triangulated only, no quads merged
  NormalsDropped,   ///< normal count mismatch or a zero/non-finite normal: normals dropped
  kCount
};
/// Why a polygon was rejected (it produces no primitives).
enum class PolygonRejection : std::uint8_t {
  TooFewVertices,   ///< fewer than 3 vertices
  NonFiniteVertex,  ///< NaN or infinite coordinate
  ZeroArea,         ///< no area left (collinear or coincident vertices)
  NotSimple,        ///< self-intersecting: ear clipping had to force ears, or its triangles
                    ///< do not tile the polygon (TriangulationResult::not_simple)
  kCount
};
std::string_view to_string(PolygonRepair r);
std::string_view to_string(PolygonRejection r);

struct ConvexQuadReport {
  std::size_t polygons = 0;   ///< polygons given
  std::size_t converted = 0;  ///< polygons that produced primitives (repaired ones included)
  std::size_t repaired = 0;   ///< polygons that needed at least one repair
  std::size_t rejected = 0;   ///< polygons that produced nothing
  std::size_t quads = 0;      ///< proper convex quads produced
  std::size_t triangles = 0;  ///< triangles produced (as quads with two equal vertices)
  std::size_t triangles_dropped = 0;  ///< convert_triangles_to_quads: degenerate input triangles
  std::array<std::size_t, static_cast<std::size_t>(PolygonRepair::kCount)> repairs{};
  std::array<std::size_t, static_cast<std::size_t>(PolygonRejection::kCount)> rejections{};

  std::size_t count(PolygonRepair r) const { return repairs[static_cast<std::size_t>(r)]; }
  std::size_t count(PolygonRejection r) const { return rejections[static_cast<std::size_t>(r)]; }
  void merge(const ConvexQuadReport& o);
  /// One line, e.g. "12 polygons: 11 converted (2 repaired: 2 collinear vertex), 1 rejected
  /// (1 zero area); 14 quads, 3 triangles".
  std::string summary() const;
};

/// A corner of a merged quad whose turning sine is below this keeps the pair as two triangles:
/// at a nearly straight corner the Jacobian of the bilinear map nearly vanishes and u, v there
/// lose accuracy like 1/sine. 1e-2 (~0.6 degrees) costs few merges. (Assumption.)
inline constexpr double kMinQuadCornerSine = 1e-2;

/// Converts one polygon (vertices counter-clockwise about its front side, possibly concave;
/// `normals` empty or one per vertex). Appends to `out` and updates `report`; returns the number
/// of primitives appended.
std::size_t convert_polygon(const std::vector<Vec3>& vertices, const std::vector<Vec3>& normals,
                            std::vector<ConvexQuad>& out, ConvexQuadReport& report);

/// Convenience: one polygon to a fresh vector.
std::vector<ConvexQuad> convert_polygon(const std::vector<Vec3>& vertices,
                                        const std::vector<Vec3>& normals, ConvexQuadReport& report);

/// Merges a triangle list (indices into `vertices`, each triangle counter-clockwise about its
/// front side) into convex quads: pairs sharing an edge (the edge used in opposite directions,
/// by at most two triangles) are merged when coplanar within kUllnerPlanarityTolerance and convex
/// with every corner sine >= kMinQuadCornerSine; the rest become triangles given as quads.
/// `normals` is empty or one per vertex. Degenerate triangles are dropped and counted.
std::vector<ConvexQuad> convert_triangles_to_quads(
    const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
    const std::vector<Vec3>& normals = {}, ConvexQuadReport* report = nullptr);

}  // namespace rtsim::geometry
