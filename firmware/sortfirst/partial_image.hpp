#pragma once
// Sort-last's partial image (seed 004 L515: "each processor ... produces an incomplete full-area
// image by transforming and rasterizing its fraction of the primitives"): a renderer's share of
// the primitives scan-converted over the whole screen, tile by tile of the rasterization layer's
// 128 x 64 buffer, as Fig. 8's appearance records (depth first). The frame buffer depth-composites
// every renderer's tile (raster::z_composite keeps the nearest record in appearance.hpp's total
// order, so the order of composition changes nothing) and shades the result
// (region_render.hpp's shade_tile): the
// frame equals the functional twin's.
#include <memory>
#include <vector>

#include "firmware/raster/region_grid.hpp"
#include "firmware/raster/region_samples.hpp"
#include "firmware/sortfirst/region_render.hpp"

namespace rtsim::sortfirst {

struct PartialImage {
  /// Tile t of raster::RegionGrid{width, height}, in order.
  std::vector<std::shared_ptr<raster::RegionSamples>> tiles;
  /// Triangles set up, samples covered, and in `shaded` the samples its own depth test kept
  /// (what a sort-last renderer shades before composition).
  RegionWork work;
};

PartialImage render_partial(const raster::RasterMesh& mesh, const raster::ViewTransform& view,
                            int width, int height, const std::vector<raster::MaterialWord>& words);

}  // namespace rtsim::sortfirst
