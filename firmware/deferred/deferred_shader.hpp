#pragma once
// A PixelFlow shading node's work on one region-sample (seed 004 L25-L53): deferred shading of
// the appearance records it received over the composition network, every pixel that needs a
// shading function shaded with it at once (SIMD), in the three parts of Fig. 7:
//
//   for each shading function present: pre-light      (textures, bump map)
//   for each light: accumulate illumination             (shadow-map lookup, diffuse, specular)
//   for each shading function present: post-light      (Phong; the alley's reflection map)
//
// The answers come only from the records and the node's table memory (the textures and the
// maps): the surface point is rebuilt from the depth word and the sample's screen position. What
// a region costs depends on what it holds, so the pass reports its work (RegionWork): the pixels
// of each function and the pixels that read each table (L148: lookup time is proportional to
// the pixels that need data).
#include <array>
#include <cstdint>
#include <vector>

#include "firmware/deferred/bowling_textures.hpp"
#include "firmware/deferred/shading_function.hpp"
#include "firmware/raster/region_samples.hpp"
#include "firmware/raster/table_maps.hpp"
#include "firmware/scene.hpp"
#include "firmware/shading/shade_params.hpp"

namespace rtsim::deferred {

/// A material's uniform parameters (sent over the geometry network, L63-L65): shader id - 1.
struct MaterialUniforms {
  ShadingFunction function = ShadingFunction::Phong;
  double kd = 1.0;
  double ks = 0.0;
  double shine = 0.0;
};

/// What is uniform over a frame: the materials, the lights, the shading model's constants.
struct ShadingSetup {
  std::vector<MaterialUniforms> materials;
  std::vector<scenes::Light> lights;
  shading::ShadeParams shade;
  Color background{0.0};
  /// The shadow test's bias, in shadow-map texels (more on steep surfaces: DepthMap::lit).
  double shadow_bias_texels = 1.5;
  /// How far the scuffs' bump map tilts the normal: the normal moves by this times the height
  /// field's slope (per texture unit).
  double bump_scale = 0.004;
};

/// A shading node's table-lookup memory: the textures and this frame's maps. A light without a
/// shadow map lights everything; no reflection map: the alley reflects nothing.
struct ShadingTables {
  const BowlingTextures* textures = nullptr;
  std::vector<const raster::DepthMap*> shadow;  ///< one per light (null: no map)
  const raster::ColourMap* reflection = nullptr;
};

/// What shading one region-sample took: the pixels of each shading function, the pixels the
/// light loop ran for, the pixels that read each table.
struct RegionWork {
  std::array<std::uint32_t, kShadingFunctions> pixels{};
  std::uint32_t lit_pixels = 0;  ///< covered pixels (every light's loop runs over them)
  std::uint32_t lights = 0;
  std::array<std::uint32_t, kLookups> lookups{};

  bool has(ShadingFunction f) const { return pixels[static_cast<std::size_t>(f)] > 0; }
  std::uint32_t lookup(Lookup l) const { return lookups[static_cast<std::size_t>(l)]; }
};

/// Shades the records of `in` seen from `view`; colours[i] for pixel i of the region (row by
/// row, kRegionWidth a row; pixels outside a partial region are background).
RegionWork shade_region(const raster::RegionSamples& in, const raster::ViewTransform& view,
                        const ShadingSetup& setup, const ShadingTables& tables,
                        std::vector<Color>& colours);

}  // namespace rtsim::deferred
