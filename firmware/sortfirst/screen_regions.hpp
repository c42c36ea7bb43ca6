#pragma once
// Sort-first's screen partition (seed 004 L560-L566): a square screen divided into equal square
// regions, one per region renderer (4 x 4, 8 x 8 and 16 x 16 in the coherence study, L568), and
// the classification of a primitive by the regions its screen bounding box covers (L503). A
// primitive that covers several regions is owned by the renderer of the upper-left one (L564).
//
// Region (row, col) of an N x N partition of a w x h screen holds the pixel columns
// [floor(col w / N), floor((col + 1) w / N)) and rows likewise; regions are numbered row by row.
#include <cstdint>

#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/view_transform.hpp"

namespace rtsim::sortfirst {

/// The regions a primitive's screen bounding box covers: columns c0..c1, rows r0..r1
/// (inclusive); `on_screen` false when the box misses the screen (nothing covered).
struct RegionRange {
  bool on_screen = false;
  int c0 = 0, c1 = -1, r0 = 0, r1 = -1;

  bool covers(int row, int col) const {
    return on_screen && row >= r0 && row <= r1 && col >= c0 && col <= c1;
  }
  int count() const { return on_screen ? (c1 - c0 + 1) * (r1 - r0 + 1) : 0; }
  friend bool operator==(const RegionRange&, const RegionRange&) = default;
};

struct ScreenRegions {
  int side = 4;  ///< N: N x N regions
  int width = 0, height = 0;

  int count() const { return side * side; }
  int x0(int col) const { return static_cast<int>(std::int64_t(col) * width / side); }
  int y0(int row) const { return static_cast<int>(std::int64_t(row) * height / side); }
  /// The region column holding pixel column x (0 <= x < width).
  int col_of(int x) const { return static_cast<int>((std::int64_t(x + 1) * side - 1) / width); }
  int row_of(int y) const { return static_cast<int>((std::int64_t(y + 1) * side - 1) / height); }
  int index(int row, int col) const { return row * side + col; }
  /// The region that owns a primitive covering `r`: its upper-left one (L564).
  int owner(const RegionRange& r) const { return index(r.r0, r.c0); }
};

/// The regions `t`'s screen bounding box covers in `view` (the triangle clipped to the near
/// plane first; back faces are classified like front faces, as the study's bounding boxes are).
RegionRange classify(const raster::RasterTriangle& t, const raster::ViewTransform& view,
                     const ScreenRegions& regions);

}  // namespace rtsim::sortfirst
