#pragma once
// A region renderer's serial renderer (seed 004 L505: "each processor performs the remaining
// transformation and rasterization steps for all of its resulting primitives"; L544: "all the
// speed-ups developed for serial renderers may be applied"): it sets up the primitives it holds
// for the frame's view, scan-converts them into its region's samples in tiles of the
// rasterization layer's 128 x 64 buffer, and shades each tile with the scene's materials and
// lights (firmware/deferred/, without shadow or reflection maps: a region renderer holds no
// other region's pixels to make them). The result is its region's finished pixels, 8 bits a
// channel, the bytes it sends to the frame buffer.
//
// Every sample keeps the nearest record in appearance.hpp's total order, so the pixels do not
// depend on the order of the primitives or on which renderer holds them: the machine's frame
// equals its functional twin's whatever the migration did (unless a record was corrupted).
#include <array>
#include <cstdint>
#include <vector>

#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/region_samples.hpp"
#include "firmware/raster/screen_triangle.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/sortfirst/screen_regions.hpp"

namespace rtsim::sortfirst {

using PixelBytes = std::array<std::uint8_t, 3>;

/// What shading needs besides the primitives: each material's record words and uniforms, the
/// lights, the textures (bowling's) when a material uses them.
struct RegionShading {
  std::vector<raster::MaterialWord> words;
  deferred::ShadingSetup setup;
  deferred::ShadingTables tables;
};

/// What rendering one region took.
struct RegionWork {
  std::uint64_t triangles = 0;  ///< set up: front-facing, not clipped away
  std::uint64_t samples = 0;    ///< samples inside a triangle (a sample per pixel)
  std::uint64_t shaded = 0;     ///< covered pixels shaded
};

struct RegionPixels {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::vector<PixelBytes> pixels;  ///< row by row, width a row
  RegionWork work;
};

/// Shades `tile` (a 128 x 64 buffer's records, sort-last's composited) into `out`'s pixels,
/// which cover it; returns the covered pixels shaded.
std::uint64_t shade_tile(const raster::RegionSamples& tile, const raster::ViewTransform& view,
                         const RegionShading& shading, RegionPixels& out);

/// Region `region` of `regions` in `view`, from `mesh` (the primitives the renderer holds for
/// it).
RegionPixels render_region(const raster::RasterMesh& mesh, const raster::ViewTransform& view,
                           const ScreenRegions& regions, int region, const RegionShading& shading);

}  // namespace rtsim::sortfirst
