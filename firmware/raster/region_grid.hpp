#pragma once
// PixelFlow's "virtual buffer" (seed 004 L21): the screen is divided into regions of 128 x 64
// pixels, one region the size of a node's SIMD array of 8K pixel processors (L148), and the
// regions are processed one at a time. A frame whose size is not a multiple of the region's has
// partial regions at its right and bottom edges; their missing pixels are simply not covered.
#include <cstdint>

namespace rtsim::raster {

inline constexpr int kRegionWidth = 128;  ///< seed 004 L21
inline constexpr int kRegionHeight = 64;  ///< seed 004 L21
/// Pixel processors in a node's SIMD array: one a pixel of a region (L148: "all 8K pixels").
inline constexpr int kRegionPixels = kRegionWidth * kRegionHeight;

/// The regions of a `width` x `height` image, numbered row by row from the top left.
struct RegionGrid {
  int width = 0;
  int height = 0;

  int columns() const { return (width + kRegionWidth - 1) / kRegionWidth; }
  int rows() const { return (height + kRegionHeight - 1) / kRegionHeight; }
  int count() const { return columns() * rows(); }
  /// The top-left pixel of region `r`.
  int x0(int r) const { return (r % columns()) * kRegionWidth; }
  int y0(int r) const { return (r / columns()) * kRegionHeight; }
  /// Its pixels inside the image (a partial region at an edge has fewer).
  int pixel_width(int r) const {
    const int w = width - x0(r);
    return w < kRegionWidth ? w : kRegionWidth;
  }
  int pixel_height(int r) const {
    const int h = height - y0(r);
    return h < kRegionHeight ? h : kRegionHeight;
  }
};

}  // namespace rtsim::raster
