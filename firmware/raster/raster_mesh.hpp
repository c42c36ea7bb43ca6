#pragma once
// The scene as a rasterizing machine holds it: triangles with a shading normal and texture
// coordinates at each vertex (seed 004 L132: the rasterizers' primitives are triangles). Polygons
// are triangulated (firmware/geometry/triangulate.hpp); spheres, cones and Bezier patches are
// tessellated at the resolutions below, which are this model's (the seed's scene is triangles
// already, L93): `mesh.*` parameters of the machine that rasterizes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/math.hpp"
#include "firmware/scene.hpp"

namespace rtsim::raster {

struct RasterVertex {
  Vec3 position{0.0};
  Vec3 normal{0.0};  ///< unit shading normal
  glm::dvec2 uv{0.0};
};

struct RasterTriangle {
  std::array<RasterVertex, 3> v{};
  /// Unit geometric normal, on the side the shading normals face (the winding's, where the
  /// surface has none of its own).
  Vec3 face_normal{0.0};
  std::uint32_t material = 0;
  std::uint32_t primitive = 0;  ///< the scene primitive it comes from
  /// Its back face is culled (a closed surface: SurfaceShading::one_sided, or a sphere).
  bool one_sided = false;
};

struct MeshSettings {
  /// Segments around a sphere (and half as many rings from pole to pole); around a cone.
  int sphere_segments = 24;
  int cone_segments = 24;
  /// A Bezier patch as a grid of this many quads a side, each two triangles.
  int patch_segments = 8;
};

struct RasterMesh {
  std::vector<RasterTriangle> triangles;
  Bounds bounds;
};

/// About how many triangles build_raster_mesh would make of `scene` (an upper bound: at most
/// one a polygon's vertex, each sphere's segments squared, each cone's and patch's grid twice),
/// without making them: a caller bounds the memory first.
double estimated_triangles(const scenes::Scene& scene, const MeshSettings& settings);

/// The scene's primitives as triangles, in scene order (each primitive's triangles together).
RasterMesh build_raster_mesh(const scenes::Scene& scene, const MeshSettings& settings);

/// The shading of material `m` (the scene's SurfaceShading, or Phong and two-sided).
const scenes::SurfaceShading& surface_shading(const scenes::Scene& scene, std::uint32_t m);

}  // namespace rtsim::raster
