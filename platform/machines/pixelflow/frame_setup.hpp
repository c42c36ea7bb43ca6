#pragma once
// What a PixelFlow frame is made of before any node runs (seed 004 L114-L128): the scene as
// triangles (the rasterizers' primitives), each material's record words and uniforms, the
// textures every shading node holds, and the views of the frame's passes — a shadow map from
// each light, a planar reflection map where a surface has the alley's shader, then the camera.
// The machine and its functional twin both start from it, so they rasterize and shade the same
// data; the twin (functional_passes.hpp) runs the passes with no timing.
#include <optional>
#include <vector>

#include "firmware/deferred/bowling_textures.hpp"
#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/screen_triangle.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/scene.hpp"

namespace rtsim::platform::pixelflow {

/// The most triangles a frame may hold (about 230 bytes each, and again in each pass's set-up):
/// a bound on memory, not a machine's limit (the bowling frame has 10,704).
inline constexpr long long kMaxTriangles = 2'000'000;

/// The image-affecting settings (the machine's `mesh.*`, `maps.*` and `shading.*` parameters).
struct FrameSettings {
  raster::MeshSettings mesh{};
  /// Texels a side of the shadow and reflection maps (L116: 512 x 512).
  int map_size = 512;
  double shadow_bias_texels = 1.5;
  double bump_scale = 0.004;
  shading::ShadeParams shade{};
};

/// The planar reflection map's pass: the camera mirrored in the reflecting surface's plane, the
/// geometry above that plane and not the reflector itself.
struct MirrorPass {
  raster::ViewTransform view;
  raster::ClipPlane plane;
  std::vector<bool> include;  ///< per material: drawn in the reflection
};

struct FrameSetup {
  int width = 0, height = 0, spp = 1;
  raster::RasterMesh mesh;
  std::vector<raster::MaterialWord> words;  ///< per material: shader id, colour bytes
  deferred::ShadingSetup shading;
  deferred::BowlingTextures textures;
  bool uses_textures = false;  ///< some material has the pin's or the alley's function
  raster::ViewTransform camera;
  /// One per light (L116-L120); empty without lights.
  std::vector<raster::ViewTransform> shadow_views;
  /// Where a material has the alley's function and the camera sees its plane (L128).
  std::optional<MirrorPass> mirror;
};

/// Builds it; throws InputError for a scene the machine cannot hold (more materials than the
/// shader id's byte can name, an unknown shading function).
FrameSetup make_frame_setup(const scenes::Scene& scene, const FrameSettings& settings, int width,
                            int height, int spp);

}  // namespace rtsim::platform::pixelflow
