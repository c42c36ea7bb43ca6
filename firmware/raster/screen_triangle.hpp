#pragma once
// A mesh triangle as one view sees it, ready to scan-convert: culled if it faces away (a closed
// surface's back), clipped in eye space to the near plane and to a guard band around the screen
// (a clipped triangle becomes a fan of triangles), projected, and its vertices snapped to a grid
// of 1/256 pixel. On that grid the edge functions are exact 64-bit integers, so triangles that
// share an edge cover each sample on it exactly once (the top-left rule, scan_convert.hpp).
//
// The rasterizer's triangle set-up (seed 004 L132: "0.85 us per front-facing triangle"); which
// triangles are front-facing is counted here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/view_transform.hpp"

namespace rtsim::raster {

/// Subpixel steps a pixel (8 bits of fraction, as fixed-point rasterizers carry).
inline constexpr int kSubpixel = 256;
/// The guard band: triangles are clipped this many pixels beyond the view's centre, which keeps
/// every snapped coordinate below 2^23 and the edge functions' products below 2^48.
inline constexpr double kGuardBandPixels = 16384.0;

/// What a sample's record says of its material: the shader id and the intrinsic colour
/// (appearance.hpp), one per scene material.
struct MaterialWord {
  std::uint8_t shader = 1;
  std::array<std::uint8_t, 3> colour{};
};

struct ScreenTriangle {
  std::array<std::int64_t, 3> x{}, y{};  ///< snapped screen positions, 1/kSubpixel pixel
  std::array<double, 3> inv_z{};         ///< 1 / eye depth at each vertex
  std::array<RasterVertex, 3> attr{};    ///< world position, shading normal, uv at each vertex
  /// The pixels its bounding box covers (inclusive), clamped to the view.
  int x_min = 0, x_max = -1, y_min = 0, y_max = -1;
  std::uint32_t triangle = 0;  ///< its mesh triangle
  MaterialWord material{};
  /// Seen from behind (a two-sided surface): its shading normals are turned to the viewer.
  bool flip = false;
};

/// A plane that keeps the side where dot(normal, p - point) >= 0 (a planar reflection map keeps
/// what lies above its mirror).
struct ClipPlane {
  Vec3 point{0.0};
  Vec3 normal{0.0, 0.0, 1.0};
};

struct ViewSetup {
  std::vector<ScreenTriangle> triangles;
  /// Mesh triangles set up: not a closed surface's back face, not wholly clipped away.
  std::size_t front_facing = 0;
};

/// Sets up every triangle of `mesh` whose material `include` allows (all, when empty) for
/// `view`, in mesh order. `materials` gives each material's record words.
ViewSetup set_up_view(const RasterMesh& mesh, const ViewTransform& view,
                      const std::vector<MaterialWord>& materials,
                      const std::vector<bool>& include = {},
                      const std::optional<ClipPlane>& clip = std::nullopt);

}  // namespace rtsim::raster
