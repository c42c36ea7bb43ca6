#pragma once
// One region-sample (seed 004 L93, L154: with 5 samples a pixel each region is rasterized and
// shaded 5 times): sample s of every pixel of one 128 x 64 region, one record a pixel processor.
// A rasterizer scan-converts its triangles into its own region-sample buffer; the composition
// network merges the rasterizers' buffers sample by sample (z_composite) and delivers the result
// to a shader. A map pass keeps depth words only (RegionDepths).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware/raster/appearance.hpp"
#include "firmware/raster/region_grid.hpp"
#include "firmware/raster/screen_triangle.hpp"

namespace rtsim::raster {

/// Where the samples of one region-sample lie: the region's pixels and the sample's offset in
/// every pixel, snapped to the subpixel grid (the offsets of firmware/tasks/vision_ray_task.hpp,
/// so a rasterized and a traced frame sample the same points).
struct RegionSampleGrid {
  int region = 0;
  int sample = 0;
  int x0 = 0, y0 = 0, width = 0, height = 0;
  int offset_x = kSubpixel / 2, offset_y = kSubpixel / 2;

  static RegionSampleGrid of(const RegionGrid& grid, int region, int sample);
  /// The screen position of the sample at pixel (x, y) of the region (x, y relative to it).
  double screen_x(int x) const { return x0 + x + double(offset_x) / kSubpixel; }
  double screen_y(int y) const { return y0 + y + double(offset_y) / kSubpixel; }
};

/// A region-sample of appearance records, kRegionWidth a row (a partial region's missing pixels
/// stay background).
struct RegionSamples {
  RegionSampleGrid at{};
  std::vector<AppearanceWord> words;

  explicit RegionSamples(const RegionSampleGrid& g)
      : at(g), words(static_cast<std::size_t>(kRegionPixels), background_word()) {}
  AppearanceWord& word(int x, int y) {
    return words[static_cast<std::size_t>(y * kRegionWidth + x)];
  }
  const AppearanceWord& word(int x, int y) const {
    return words[static_cast<std::size_t>(y * kRegionWidth + x)];
  }
};

/// A region-sample of depth words only (a shadow map's pass, seed 004 L118).
struct RegionDepths {
  RegionSampleGrid at{};
  std::vector<std::uint32_t> depth;

  explicit RegionDepths(const RegionSampleGrid& g)
      : at(g), depth(static_cast<std::size_t>(kRegionPixels), kBackgroundDepth) {}
};

/// What scan-converting one triangle into a region-sample did.
struct ScanCount {
  std::size_t covered = 0;  ///< samples inside the triangle
  std::size_t written = 0;  ///< of those, nearer than what the buffer held
};

/// Scan-converts `t` into `into`: every sample of the region inside the triangle (top-left rule
/// on the edges) gets the triangle's record where it is nearer (appearance.hpp's order).
ScanCount scan_convert(const ScreenTriangle& t, const ViewTransform& view, RegionSamples& into);
/// The same for depth only.
ScanCount scan_depth(const ScreenTriangle& t, const ViewTransform& view, RegionDepths& into);

/// Sample by sample, keeps the nearer record of `into` and `from` (the composition network's
/// z-compositing, L21, L120). Returns the samples `from` won.
std::size_t z_composite(RegionSamples& into, const RegionSamples& from);
std::size_t z_composite(RegionDepths& into, const RegionDepths& from);

}  // namespace rtsim::raster
