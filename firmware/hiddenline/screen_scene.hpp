#pragma once
// A scene as the hidden-line pipeline takes it (seed 000 §3.4): convex polygons and line
// segments in integer screen coordinates, the machine's 16-bit numbers (L1906). The scene's
// polygons are the hiding polygons and their edges the segments (L1697: "polygon edges, rather
// than complete polygons, pass through the pipeline"); a concave polygon hides as the triangles
// it is cut into, while its segments stay its own edges, so the drawing shows no artefact of the
// split (L1898). Spheres, cones and Bézier patches are their tessellation's triangles, each
// triangle edge a segment (shared edges once).
//
// Each polygon and segment is clipped in eye space to the near plane and to a guard band one
// screen width and height round the view, then projected: x and y map the guard band onto
// [0, 2^16), and depth is 1/z mapped onto [0, 2^16) between the nearest and the farthest
// depth of what was kept (a projective depth, so a plane stays a plane on the screen; the
// view's own near and far would crowd a scene far from its near plane into a few values). Coordinates are rounded to
// integers; a polygon's boundary planes are exact for those integers (plane.hpp), and so the
// pipe's results are exact to the numbers' precision (L1681).
#include <cstdint>
#include <vector>

#include "firmware/hiddenline/messages.hpp"
#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/scene.hpp"

namespace rtsim::hiddenline {

/// Screen coordinates' range: [0, kScreenUnits).
inline constexpr std::int32_t kScreenUnits = 1 << 16;

struct ScreenScene {
  std::vector<std::vector<ScreenPoint>> polygons;  ///< convex, in front of the eye
  std::vector<Segment> segments;                   ///< `edge` numbers them in order
  /// Screen units a pixel, and the pixel position of screen unit 0 (x and y).
  double units_per_pixel = 1.0;
  double origin_x = 0.0, origin_y = 0.0;
  std::size_t concave_split = 0;  ///< concave polygons cut into triangles
  std::size_t clipped = 0;        ///< polygons the near plane or the guard band cut
  std::size_t culled = 0;         ///< polygons wholly outside them

  /// A screen point's pixel position.
  double pixel_x(double x) const { return origin_x + x / units_per_pixel; }
  double pixel_y(double y) const { return origin_y + y / units_per_pixel; }
};

/// The scene seen from `view` (its near and far bound the depth); `mesh` tessellates the
/// primitives that are not polygons (build_raster_mesh).
ScreenScene to_screen(const scenes::Scene& scene, const raster::RasterMesh& mesh,
                      const raster::ViewTransform& view);

}  // namespace rtsim::hiddenline
